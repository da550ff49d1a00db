// Decoding of the base mesh stream (Draco-coded triangle mesh).
#ifndef MESHVID_CODEC_DEC_BASE_MESH_DECODER_H_
#define MESHVID_CODEC_DEC_BASE_MESH_DECODER_H_

#include <cstdint>
#include <span>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// Decodes a Draco-coded triangle mesh (positions and triangles; other attributes ignored).
/// The vertex order is Draco's: encoder and decoder both use this decoded mesh, so they agree.
/// Fails with kCorrupt on malformed input and on a mesh that does not pass ValidateMesh.
StatusOr<TriangleMesh> DecodeBaseMesh(std::span<const std::uint8_t> bytes);

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_BASE_MESH_DECODER_H_
