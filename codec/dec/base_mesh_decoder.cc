#include "codec/dec/base_mesh_decoder.h"

#include <array>
#include <string>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

namespace meshvid {

StatusOr<TriangleMesh> DecodeBaseMesh(std::span<const std::uint8_t> bytes) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) {
    return CorruptError("base mesh: Draco cannot decode it: " +
                        decoded.status().error_msg_string());
  }
  const std::unique_ptr<draco::Mesh> draco_mesh = std::move(decoded).value();
  const draco::PointAttribute* position =
      draco_mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  // Draco decodes positions (quantised or not) to 32-bit floats. They are copied as such:
  // Draco's ConvertValue reads the attribute's `normalized` flag, a bool Draco fills from a
  // byte of the stream (any value: undefined behaviour in its header, found by fuzzing).
  if (position == nullptr || position->num_components() != 3 ||
      position->data_type() != draco::DT_FLOAT32 || position->byte_stride() != 12) {
    return CorruptError("base mesh: no position attribute of 3 32-bit floats");
  }
  TriangleMesh mesh;
  mesh.positions.resize(draco_mesh->num_points());
  for (draco::PointIndex i(0); i < draco_mesh->num_points(); ++i) {
    std::array<float, 3> xyz;  // GetValue checks the read against the attribute's buffer
    if (!position->GetValue<float, 3>(position->mapped_index(i), &xyz)) {
      return CorruptError("base mesh: unreadable position of point " +
                          std::to_string(i.value()));
    }
    mesh.positions[i.value()] = Eigen::Vector3f(xyz[0], xyz[1], xyz[2]);
  }
  mesh.triangles.resize(draco_mesh->num_faces());
  for (draco::FaceIndex f(0); f < draco_mesh->num_faces(); ++f) {
    const draco::Mesh::Face& face = draco_mesh->face(f);
    mesh.triangles[f.value()] = Triangle(face[0].value(), face[1].value(), face[2].value());
  }
  MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, "base mesh"));
  return mesh;
}

}  // namespace meshvid
