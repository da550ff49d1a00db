#include "codec/dec/base_mesh_decoder.h"

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
  if (position == nullptr || position->num_components() != 3) {
    return CorruptError("base mesh: no 3-component position attribute");
  }
  TriangleMesh mesh;
  mesh.positions.resize(draco_mesh->num_points());
  for (draco::PointIndex i(0); i < draco_mesh->num_points(); ++i) {
    float xyz[3];
    if (!position->ConvertValue<float, 3>(position->mapped_index(i), xyz)) {
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
