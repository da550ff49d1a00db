// Decoding of the base mesh stream (Draco-coded triangle mesh).
#ifndef MESHVID_CODEC_DEC_BASE_MESH_DECODER_H_
#define MESHVID_CODEC_DEC_BASE_MESH_DECODER_H_

#include <cstdint>
#include <span>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// Most triangles a base mesh may have (and three times as many vertices). Base meshes are
/// coarse (the reference encoder's are tens of thousands of triangles); the cap bounds what a
/// damaged stream can make the decoder allocate.
inline constexpr std::uint32_t kMaxBaseMeshTriangles = 1u << 22;

/// Whether DecodeBaseMesh reads a COLOR attribute.
enum class VertexColours {
  kIgnore,  ///< positions and triangles only (a `.mvid` base mesh)
  kRead,    ///< also a COLOR attribute of 3 unsigned bytes, when the stream has one
};

/// Decodes a Draco-coded triangle mesh (positions and triangles; other attributes ignored
/// unless `colours` asks for vertex colours).
/// The vertex order is Draco's: encoder and decoder both use this decoded mesh, so they agree.
/// Fails with kCorrupt on malformed input, on a stream that is not a Draco 2.2 triangle mesh
/// without metadata, on counts over kMaxBaseMeshTriangles, and on a mesh that does not pass
/// ValidateMesh.
StatusOr<TriangleMesh> DecodeBaseMesh(std::span<const std::uint8_t> bytes,
                                      VertexColours colours = VertexColours::kIgnore);

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_BASE_MESH_DECODER_H_
