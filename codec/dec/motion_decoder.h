// Decoding of the motion streams: the MOTN payload (segments and blend weights) and the
// per-group transform payloads (a quantised rigid transform per segment per frame).
#ifndef MESHVID_CODEC_DEC_MOTION_DECODER_H_
#define MESHVID_CODEC_DEC_MOTION_DECODER_H_

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/common/motion.h"
#include "format/status.h"

namespace meshvid {

/// Quantisation steps of the transform tracks, stated in the MOTN payload.
struct MotionQuantization {
  float rotation_step = 1.0f / 65536;     ///< radians per unit of the rotation vector
  float translation_step = 1.0f / 65536;  ///< capture units per unit of the translation
};

/// A transform as stored: rotation vector (axis * angle) and translation, in steps.
struct QuantizedTransform {
  std::array<std::int32_t, 3> rotation{};
  std::array<std::int32_t, 3> translation{};
  bool operator==(const QuantizedTransform&) const = default;
};

/// The transform a quantised one stands for.
RigidTransform DequantizeTransform(const QuantizedTransform& q,
                                   const MotionQuantization& quantization);

/// The decoded MOTN payload.
struct DecodedMotion {
  MotionModel model;
  MotionQuantization quantization;
};

/// Decodes a MOTN payload (version 1, 2 or 3) for a base mesh of `vertex_count` vertices and
/// `triangle_count` triangles. A version 3 model holds nodes (MotionModel::node_vertices) and
/// no blends yet: codec/common/deformation_graph.h's CompleteNodeBlends derives them from the
/// base mesh.
StatusOr<DecodedMotion> DecodeMotionModel(std::span<const std::uint8_t> payload,
                                          std::size_t vertex_count,
                                          std::size_t triangle_count = 0);

/// How a transform payload orders the bytes of its zig-zag deltas (spec/mvid-codec.md, GOF
/// side information): each delta's 4 little-endian bytes together (side_info_version 1), or
/// byte planes, every delta's lowest byte first, then every second byte and so on (version 2,
/// what encoders write: zstd finds the planes' runs of zero high bytes).
enum class TransformByteOrder : std::uint8_t { kInterleaved, kBytePlanes };

/// Decodes one group's transforms: result[frame][segment]. The group must hold
/// `frame_count` frames of `segment_count` segments (as the container and MOTN say).
StatusOr<std::vector<std::vector<RigidTransform>>> DecodeTransforms(
    std::span<const std::uint8_t> payload, std::uint32_t frame_count,
    std::uint32_t segment_count, const MotionQuantization& quantization,
    TransformByteOrder order = TransformByteOrder::kBytePlanes);

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_MOTION_DECODER_H_
