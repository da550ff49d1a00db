#include "codec/enc/base_mesh_encoder.h"

#include <string>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/encode.h>
#include <draco/core/encoder_buffer.h>
#include <draco/mesh/mesh.h>

#include "codec/dec/base_mesh_decoder.h"

namespace meshvid {

StatusOr<EncodedBaseMesh> EncodeBaseMesh(const TriangleMesh& mesh,
                                         const BaseMeshEncoding& settings) {
  MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, "base mesh"));
  if (settings.position_bits < 1 || settings.position_bits > 30) {
    return InvalidArgumentError("base mesh position bits must be in 1..30, got " +
                                std::to_string(settings.position_bits));
  }
  draco::Mesh draco_mesh;
  draco_mesh.set_num_points(static_cast<std::uint32_t>(mesh.vertex_count()));
  draco::GeometryAttribute attribute;
  attribute.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false,
                 sizeof(float) * 3, 0);
  const int position_id =
      draco_mesh.AddAttribute(attribute, /*identity_mapping=*/true, mesh.vertex_count());
  draco::PointAttribute* position = draco_mesh.attribute(position_id);
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    position->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(i)),
                                mesh.positions[i].data());
  }
  draco_mesh.SetNumFaces(mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    draco::Mesh::Face face;
    for (int c = 0; c < 3; ++c) face[c] = draco::PointIndex(mesh.triangles[t][c]);
    draco_mesh.SetFace(draco::FaceIndex(static_cast<std::uint32_t>(t)), face);
  }

  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, settings.position_bits);
  encoder.SetSpeedOptions(settings.encoding_speed, settings.encoding_speed);
  encoder.SetEncodingMethod(settings.preserve_order ? draco::MESH_SEQUENTIAL_ENCODING
                                                    : draco::MESH_EDGEBREAKER_ENCODING);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(draco_mesh, &buffer);
  if (!status.ok()) return InternalError("Draco cannot encode the base mesh: " +
                                         status.error_msg_string());

  EncodedBaseMesh result;
  result.bytes.assign(buffer.data(), buffer.data() + buffer.size());
  MESHVID_ASSIGN_OR_RETURN(result.decoded, DecodeBaseMesh(result.bytes));
  return result;
}

}  // namespace meshvid
