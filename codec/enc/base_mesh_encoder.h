// Encoding of the base mesh stream with Draco.
#ifndef MESHVID_CODEC_ENC_BASE_MESH_ENCODER_H_
#define MESHVID_CODEC_ENC_BASE_MESH_ENCODER_H_

#include <cstdint>
#include <vector>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// Settings of the Draco base-mesh coder.
struct BaseMeshEncoding {
  int position_bits = 16;   ///< position quantisation (Draco: 1..30 bits per coordinate)
  int encoding_speed = 0;   ///< Draco speed, 0 (best compression) .. 10 (fastest)
  /// Draco's sequential coder keeps vertex and triangle order, so data indexed by base vertex
  /// (blend weights, the subdivision lattice) needs no remapping; edgebreaker codes smaller
  /// but renumbers. The base mesh is coded once per file, so order wins by default.
  bool preserve_order = true;
};

/// A coded base mesh and the mesh a decoder will reconstruct from it (Draco reorders vertices
/// and quantises positions): everything downstream must be computed against `decoded`.
struct EncodedBaseMesh {
  std::vector<std::uint8_t> bytes;
  TriangleMesh decoded;
};

/// Codes positions and triangles with Draco and decodes the result again.
StatusOr<EncodedBaseMesh> EncodeBaseMesh(const TriangleMesh& mesh,
                                         const BaseMeshEncoding& settings = {});

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_BASE_MESH_ENCODER_H_
