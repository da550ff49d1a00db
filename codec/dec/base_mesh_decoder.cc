#include "codec/dec/base_mesh_decoder.h"

#include <array>
#include <string>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

#include "format/byte_io.h"

namespace meshvid {

namespace {

/// Reads a Draco varUI32 (7 bits per byte, least significant group first, at most 5 bytes).
StatusOr<std::uint32_t> ReadDracoVarU32(ByteReader& reader, std::string_view what) {
  std::uint64_t value = 0;
  for (int shift = 0; shift < 35; shift += 7) {
    MESHVID_ASSIGN_OR_RETURN(const std::uint8_t byte, reader.ReadU8(what));
    value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
    if ((byte & 0x80) == 0) {
      if (value > 0xffffffffu) break;
      return static_cast<std::uint32_t>(value);
    }
  }
  return reader.Error(std::string(what) + " is not a 32-bit varint");
}

/// Checks the Draco header and the connectivity counts before Draco sees the stream: a
/// triangle mesh of the bitstream version Draco 1.5 writes (2.2), no metadata, and counts
/// within kMaxBaseMeshTriangles (Draco allocates its connectivity from the declared counts
/// before it reads a symbol, so a few forged bytes could otherwise ask for gigabytes).
Status CheckDracoHeader(std::span<const std::uint8_t> bytes) {
  ByteReader reader(bytes, "base mesh");
  MESHVID_ASSIGN_OR_RETURN(const auto magic, reader.ReadBytes(5, "Draco magic"));
  if (std::string_view(reinterpret_cast<const char*>(magic.data()), 5) != "DRACO") {
    return reader.Error("not a Draco stream (no DRACO magic)");
  }
  MESHVID_ASSIGN_OR_RETURN(const std::uint8_t major, reader.ReadU8("Draco major version"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint8_t minor, reader.ReadU8("Draco minor version"));
  if (major != draco::kDracoMeshBitstreamVersionMajor ||
      minor != draco::kDracoMeshBitstreamVersionMinor) {
    return reader.Error("Draco bitstream version " + std::to_string(major) + "." +
                        std::to_string(minor) + " is not the version 2.2 this format uses");
  }
  MESHVID_ASSIGN_OR_RETURN(const std::uint8_t encoder_type, reader.ReadU8("Draco encoder type"));
  if (encoder_type != draco::TRIANGULAR_MESH) return reader.Error("Draco stream is not a mesh");
  MESHVID_ASSIGN_OR_RETURN(const std::uint8_t method, reader.ReadU8("Draco encoder method"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint16_t flags, reader.ReadU16("Draco flags"));
  if (flags & METADATA_FLAG_MASK) return reader.Error("Draco stream carries metadata");
  std::uint32_t triangles = 0;
  std::uint32_t vertices = 0;
  if (method == draco::MESH_SEQUENTIAL_ENCODING) {  // faces, then points
    MESHVID_ASSIGN_OR_RETURN(triangles, ReadDracoVarU32(reader, "Draco face count"));
    MESHVID_ASSIGN_OR_RETURN(vertices, ReadDracoVarU32(reader, "Draco point count"));
  } else if (method == draco::MESH_EDGEBREAKER_ENCODING) {  // traversal, vertices, faces
    MESHVID_RETURN_IF_ERROR(reader.Skip(1, "Draco traversal type"));
    MESHVID_ASSIGN_OR_RETURN(vertices, ReadDracoVarU32(reader, "Draco vertex count"));
    MESHVID_ASSIGN_OR_RETURN(triangles, ReadDracoVarU32(reader, "Draco face count"));
  } else {
    return reader.Error("unknown Draco encoder method " + std::to_string(method));
  }
  if (triangles > kMaxBaseMeshTriangles || vertices > 3 * std::uint64_t{kMaxBaseMeshTriangles}) {
    return reader.Error("Draco stream declares " + std::to_string(triangles) + " triangles and " +
                        std::to_string(vertices) + " vertices, more than a base mesh may have (" +
                        std::to_string(kMaxBaseMeshTriangles) + " triangles)");
  }
  return Status::Ok();
}

}  // namespace

StatusOr<TriangleMesh> DecodeBaseMesh(std::span<const std::uint8_t> bytes, VertexColours colours) {
  MESHVID_RETURN_IF_ERROR(CheckDracoHeader(bytes));
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
  const draco::PointAttribute* colour =
      colours == VertexColours::kRead
          ? draco_mesh->GetNamedAttribute(draco::GeometryAttribute::COLOR)
          : nullptr;
  if (colour != nullptr) {
    if (colour->num_components() != 3 || colour->data_type() != draco::DT_UINT8 ||
        colour->byte_stride() != 3) {
      return CorruptError("base mesh: a colour attribute that is not 3 unsigned bytes");
    }
    mesh.colours.resize(mesh.positions.size());
    for (draco::PointIndex i(0); i < draco_mesh->num_points(); ++i) {
      std::array<std::uint8_t, 3> rgb;
      if (!colour->GetValue<std::uint8_t, 3>(colour->mapped_index(i), &rgb)) {
        return CorruptError("base mesh: unreadable colour of point " + std::to_string(i.value()));
      }
      mesh.colours[i.value()] = Colour(rgb[0], rgb[1], rgb[2]);
    }
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
