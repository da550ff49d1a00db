// Encoding of the base mesh stream with Draco.
#ifndef MESHVID_CODEC_ENC_CODING_BASE_MESH_ENCODER_H_
#define MESHVID_CODEC_ENC_CODING_BASE_MESH_ENCODER_H_

#include <cstdint>
#include <vector>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// Settings of the Draco base-mesh coder.
struct BaseMeshEncoding {
  int position_bits = 16;   ///< position quantisation (Draco: 1..30 bits per coordinate)
  int encoding_speed = 0;   ///< Draco speed, 0 (best compression) .. 10 (fastest)
  /// Edgebreaker codes several times smaller than the sequential coder
  /// (bench/DESIGN-NOTES.md) but renumbers vertices and triangles; data indexed by base vertex
  /// or triangle is then moved to the decoder's order (EncodedBaseMesh::vertex_in_decoded).
  /// It is used when every input vertex is found again, one to one, within a quantisation
  /// step; otherwise (or when false) the sequential coder, which keeps the order.
  bool try_edgebreaker = true;
  /// Edgebreaker whatever order it gives back: for meshes nothing else indexes by vertex (a
  /// per-frame stream, as the benchmark's baseline codes).
  bool allow_reorder = false;
  /// Codes the mesh's vertex colours too, when it has one per vertex, as Draco's COLOR
  /// attribute (3 unsigned bytes, lossless), and decodes them back: for per-frame streams (the
  /// benchmark's baseline). A `.mvid` base mesh carries positions only.
  bool code_colours = false;
};

/// A coded base mesh and the mesh a decoder will reconstruct from it (Draco may reorder
/// vertices and triangles, and quantises positions): everything downstream must be computed
/// against `decoded`.
struct EncodedBaseMesh {
  std::vector<std::uint8_t> bytes;
  TriangleMesh decoded;
  /// Per input vertex, its index in `decoded` (empty: the same order, or allow_reorder).
  std::vector<std::uint32_t> vertex_in_decoded;
  /// Per input triangle, its index in `decoded` (empty as above).
  std::vector<std::uint32_t> triangle_in_decoded;
  int position_bits = 0;  ///< the quantisation the stream uses (see kEdgebreakerExtraBits)
};

/// Where edgebreaker's vertices cannot be matched to the input's at the asked quantisation
/// (two vertices within a step that nothing tells apart), it is tried again with up to this
/// many bits more before the sequential method (several times larger) is used.
inline constexpr int kEdgebreakerExtraBits = 4;

/// Codes positions and triangles with Draco and decodes the result again.
StatusOr<EncodedBaseMesh> EncodeBaseMesh(const TriangleMesh& mesh,
                                         const BaseMeshEncoding& settings = {});

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_CODING_BASE_MESH_ENCODER_H_
