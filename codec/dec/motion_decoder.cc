#include "codec/dec/motion_decoder.h"

#include <bit>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "codec/common/compression.h"
#include "format/byte_io.h"

namespace meshvid {
namespace {

/// Versions this decoder reads: 1 (no surface mask), 2 (with one), 3 (deformation nodes).
constexpr std::uint8_t kMotionVersionMin = kMotionVersionWithoutMask;
constexpr std::uint8_t kMotionVersionMax = kMotionVersionNodes;
/// Bytes of one vertex blend in the raw MOTN body: count + 4 x (u32 segment, u16 weight).
constexpr std::size_t kBlendBytes = 1 + kMaxInfluences * 6;
/// Bytes of one transform in the raw transform body: 6 zig-zag u32.
constexpr std::size_t kTransformBytes = 24;

/// Adds a zig-zag coded delta with wrap-around (corrupt input must not overflow).
std::int32_t AddZigZagDelta(std::int32_t value, std::uint32_t zigzag) {
  const std::uint32_t delta = (zigzag >> 1) ^ (~(zigzag & 1) + 1);
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(value) + delta);
}

}  // namespace

RigidTransform DequantizeTransform(const QuantizedTransform& q,
                                   const MotionQuantization& quantization) {
  RigidTransform t;
  const Eigen::Vector3f rotation_vector(q.rotation[0] * quantization.rotation_step,
                                        q.rotation[1] * quantization.rotation_step,
                                        q.rotation[2] * quantization.rotation_step);
  const float angle = rotation_vector.norm();
  t.rotation = angle > 0 ? Eigen::Quaternionf(Eigen::AngleAxisf(angle, rotation_vector / angle))
                         : Eigen::Quaternionf::Identity();
  t.translation = Eigen::Vector3f(q.translation[0] * quantization.translation_step,
                                  q.translation[1] * quantization.translation_step,
                                  q.translation[2] * quantization.translation_step);
  return t;
}

StatusOr<DecodedMotion> DecodeMotionModel(std::span<const std::uint8_t> payload,
                                          std::size_t vertex_count, std::size_t triangle_count) {
  ByteReader reader(payload, "motion (MOTN)");
  MESHVID_ASSIGN_OR_RETURN(const std::uint8_t version, reader.ReadU8("motion_version"));
  if (version < kMotionVersionMin || version > kMotionVersionMax) {
    return UnsupportedError("motion (MOTN): version " + std::to_string(version) +
                            " is not supported (this decoder reads versions 1 to 3)");
  }
  DecodedMotion result;
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t rotation_bits, reader.ReadU32("rotation_step"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t translation_bits,
                           reader.ReadU32("translation_step"));
  result.quantization.rotation_step = std::bit_cast<float>(rotation_bits);
  result.quantization.translation_step = std::bit_cast<float>(translation_bits);
  if (!(result.quantization.rotation_step > 0 && result.quantization.rotation_step < 1) ||
      !(result.quantization.translation_step > 0 &&
        std::isfinite(result.quantization.translation_step))) {
    return reader.Error("quantisation steps must be positive and finite");
  }
  MESHVID_ASSIGN_OR_RETURN(result.model.segment_count, reader.ReadU32("segment_count"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t stored_vertices, reader.ReadU32("vertex_count"));
  if (stored_vertices != vertex_count) {
    return reader.Error("vertex_count " + std::to_string(stored_vertices) +
                        " differs from the base mesh's " + std::to_string(vertex_count));
  }
  if (result.model.segment_count == 0 || result.model.segment_count > vertex_count) {
    return reader.Error("segment_count " + std::to_string(result.model.segment_count) +
                        " is not in 1..vertex_count");
  }
  std::uint32_t mask_triangles = 0;
  if (version >= 2) {
    MESHVID_ASSIGN_OR_RETURN(mask_triangles, reader.ReadU32("mask_triangle_count"));
    if (mask_triangles != 0 && mask_triangles != triangle_count) {
      return reader.Error("mask_triangle_count " + std::to_string(mask_triangles) +
                          " differs from the base mesh's " + std::to_string(triangle_count) +
                          " triangles");
    }
  }
  const bool nodes = version == kMotionVersionNodes;
  if (nodes) {
    MESHVID_ASSIGN_OR_RETURN(const std::uint32_t spacing_bits, reader.ReadU32("node_spacing"));
    result.model.node_spacing = std::bit_cast<float>(spacing_bits);
    if (!(result.model.node_spacing > 0) || !std::isfinite(result.model.node_spacing)) {
      return reader.Error("node_spacing must be positive and finite");
    }
  }
  const std::size_t mask_bytes = (std::size_t(mask_triangles) + 7) / 8;
  // Version 3 stores a u32 per node (segment), the others a blend per vertex.
  const std::size_t head_bytes =
      nodes ? std::size_t(result.model.segment_count) * 4 : vertex_count * kBlendBytes;
  MESHVID_ASSIGN_OR_RETURN(
      const std::vector<std::uint8_t> body,
      DecompressBlock(payload.subspan(reader.position()), head_bytes + mask_bytes,
                      "motion (MOTN) blend weights"));
  ByteReader blends(body, "motion (MOTN) blend weights");
  if (nodes) result.model.node_vertices.resize(result.model.segment_count);
  for (std::uint32_t& v : result.model.node_vertices) {
    MESHVID_ASSIGN_OR_RETURN(v, blends.ReadU32("node vertex"));
    if (v >= vertex_count) {
      return blends.Error("node vertex " + std::to_string(v) + " is not a base vertex");
    }
  }
  result.model.blends.resize(nodes ? 0 : vertex_count);
  for (std::size_t v = 0; v < result.model.blends.size(); ++v) {
    VertexBlend& blend = result.model.blends[v];
    MESHVID_ASSIGN_OR_RETURN(blend.count, blends.ReadU8("influence count"));
    if (blend.count == 0 || blend.count > kMaxInfluences) {
      return blends.Error("vertex " + std::to_string(v) + " has " +
                          std::to_string(blend.count) + " influences");
    }
    float remaining = 1.0f;
    for (int i = 0; i < kMaxInfluences; ++i) {
      MESHVID_ASSIGN_OR_RETURN(const std::uint32_t segment, blends.ReadU32("segment"));
      MESHVID_ASSIGN_OR_RETURN(const std::uint16_t weight, blends.ReadU16("weight"));
      if (i >= blend.count) continue;
      // The last influence takes what the others leave, so weights sum to 1 exactly.
      const float w = i + 1 == blend.count ? remaining : weight / 65535.0f;
      blend.influences[i] = {segment, w};
      remaining -= w;
    }
  }
  result.model.surface_triangles.resize(mask_triangles);
  for (std::size_t t = 0; t < mask_triangles; ++t) {
    result.model.surface_triangles[t] = (body[head_bytes + t / 8] >> (t % 8)) & 1;
  }
  // Version 3's blends need the base mesh (CompleteNodeBlends); the others are checked here.
  if (!nodes) MESHVID_RETURN_IF_ERROR(ValidateMotionModel(result.model, vertex_count));
  return result;
}

StatusOr<std::vector<std::vector<RigidTransform>>> DecodeTransforms(
    std::span<const std::uint8_t> payload, std::uint32_t frame_count,
    std::uint32_t segment_count, const MotionQuantization& quantization,
    TransformByteOrder order) {
  ByteReader reader(payload, "transforms");
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t stored_frames, reader.ReadU32("frame_count"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t stored_segments, reader.ReadU32("segment_count"));
  if (stored_frames != frame_count || stored_segments != segment_count) {
    return reader.Error("holds " + std::to_string(stored_frames) + " frames x " +
                        std::to_string(stored_segments) + " segments, expected " +
                        std::to_string(frame_count) + " x " + std::to_string(segment_count));
  }
  // The counts come from the file: check them against what the coded bytes can expand to
  // before anything is allocated for them (the product of two u32 fits in 64 bits).
  const std::span<const std::uint8_t> coded = payload.subspan(reader.position());
  const std::uint64_t transforms = std::uint64_t{frame_count} * segment_count;
  if (transforms > std::numeric_limits<std::size_t>::max() / kTransformBytes ||
      !ZstdCanExpandTo(coded.size(), transforms * kTransformBytes)) {
    return reader.Error(std::to_string(frame_count) + " frames x " +
                        std::to_string(segment_count) + " segments need more transform bytes "
                        "than " + std::to_string(coded.size()) + " coded bytes can hold");
  }
  MESHVID_ASSIGN_OR_RETURN(
      std::vector<std::uint8_t> body,
      DecompressBlock(coded, static_cast<std::size_t>(transforms * kTransformBytes),
                      "transforms"));
  if (order == TransformByteOrder::kBytePlanes) body = JoinBytePlanes(body);
  ByteReader values(body, "transforms");
  std::vector<std::vector<RigidTransform>> frames(frame_count);
  // Each frame is coded as the difference from the previous one (the first from zero).
  std::vector<QuantizedTransform> previous(segment_count);
  for (std::uint32_t f = 0; f < frame_count; ++f) {
    frames[f].resize(segment_count);
    for (std::uint32_t s = 0; s < segment_count; ++s) {
      QuantizedTransform& q = previous[s];
      for (int c = 0; c < 3; ++c) {
        MESHVID_ASSIGN_OR_RETURN(const std::uint32_t d, values.ReadU32("rotation delta"));
        q.rotation[c] = AddZigZagDelta(q.rotation[c], d);
      }
      for (int c = 0; c < 3; ++c) {
        MESHVID_ASSIGN_OR_RETURN(const std::uint32_t d, values.ReadU32("translation delta"));
        q.translation[c] = AddZigZagDelta(q.translation[c], d);
      }
      frames[f][s] = DequantizeTransform(q, quantization);
    }
  }
  return frames;
}

}  // namespace meshvid
