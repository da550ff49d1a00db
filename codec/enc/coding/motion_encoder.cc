#include "codec/enc/coding/motion_encoder.h"

#include <algorithm>
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

std::uint32_t ZigZagDelta(std::int32_t from, std::int32_t to) {
  const auto delta = static_cast<std::int32_t>(static_cast<std::uint32_t>(to) -
                                               static_cast<std::uint32_t>(from));
  return (static_cast<std::uint32_t>(delta) << 1) ^ static_cast<std::uint32_t>(delta >> 31);
}

std::int32_t QuantizeValue(float value, float step) {
  const double q = std::nearbyint(static_cast<double>(value) / step);
  constexpr double kLimit = std::numeric_limits<std::int32_t>::max();
  return static_cast<std::int32_t>(std::clamp(q, -kLimit, kLimit));
}

Status CheckQuantization(const MotionQuantization& q) {
  if (!(q.rotation_step > 0 && q.rotation_step < 1) ||
      !(q.translation_step > 0 && std::isfinite(q.translation_step))) {
    return InvalidArgumentError("motion quantisation steps must be positive and finite");
  }
  return Status::Ok();
}

}  // namespace

QuantizedTransform QuantizeTransform(const RigidTransform& transform,
                                     const MotionQuantization& quantization,
                                     const Eigen::Vector3f& pivot) {
  // The rotation vector of the shortest rotation (angle in [0, pi]).
  Eigen::Quaternionf r = transform.rotation.normalized();
  if (r.w() < 0) r.coeffs() = -r.coeffs();
  const Eigen::AngleAxisf angle_axis(r);
  const Eigen::Vector3f rotation_vector = angle_axis.angle() * angle_axis.axis();
  QuantizedTransform q;
  for (int c = 0; c < 3; ++c) {
    q.rotation[c] = QuantizeValue(rotation_vector[c], quantization.rotation_step);
  }
  // Where the pivot goes, kept by the translation under the rotation a decoder will use.
  const Eigen::Vector3f translation = transform.rotation * pivot + transform.translation -
                                      DequantizeTransform(q, quantization).rotation * pivot;
  for (int c = 0; c < 3; ++c) {
    q.translation[c] = QuantizeValue(translation[c], quantization.translation_step);
  }
  return q;
}

MotionPivots FindMotionPivots(const MotionModel& model,
                              std::span<const Eigen::Vector3f> positions) {
  std::vector<Eigen::AlignedBox3f> boxes(model.segment_count);
  for (std::size_t v = 0; v < model.blends.size() && v < positions.size(); ++v) {
    const VertexBlend& blend = model.blends[v];
    for (int i = 0; i < blend.count; ++i) {
      const std::uint32_t segment = blend.influences[i].segment;
      if (segment < boxes.size() && blend.influences[i].weight > 0)
        boxes[segment].extend(positions[v]);
    }
  }
  MotionPivots result;
  result.pivots.reserve(boxes.size());
  for (const Eigen::AlignedBox3f& box : boxes) {
    result.pivots.push_back(box.isEmpty() ? Eigen::Vector3f(Eigen::Vector3f::Zero())
                                          : Eigen::Vector3f(box.center()));
    // Half the box's diagonal bounds the distance from its centre to any vertex in it.
    if (!box.isEmpty()) result.reach = std::max(result.reach, 0.5f * box.diagonal().norm());
  }
  return result;
}

float RotationStepForReach(const MotionQuantization& quantization, float reach) {
  // A rotation vector rounded to step s is off by at most s * sqrt(3) / 2 radians, which moves
  // a point at distance `reach` from the pivot by at most that times `reach`; the translation's
  // own rounding moves it by at most translation_step * sqrt(3) / 2. The rotation is held to a
  // quarter of that: its rounding jitters the posed surface from frame to frame, which the
  // displacement video pays for (bench/TRANSFORMS.md).
  constexpr float kRotationShareOfBound = 0.25f;
  const float step =
      reach > 0 ? kRotationShareOfBound * quantization.translation_step / reach : 0.5f;
  return std::max(quantization.rotation_step, std::min(0.5f, step));
}

StatusOr<std::vector<std::uint8_t>> EncodeMotionModel(const MotionModel& model,
                                                      const MotionQuantization& quantization) {
  MESHVID_RETURN_IF_ERROR(CheckQuantization(quantization));
  MESHVID_RETURN_IF_ERROR(ValidateMotionModel(model, model.blends.size()));
  ByteWriter header;
  const bool masked = !model.surface_triangles.empty();
  const bool nodes = !model.node_vertices.empty();
  header.PutU8(nodes    ? kMotionVersionNodes
               : masked ? kMotionVersionWithMask
                        : kMotionVersionWithoutMask);
  header.PutU32(std::bit_cast<std::uint32_t>(quantization.rotation_step));
  header.PutU32(std::bit_cast<std::uint32_t>(quantization.translation_step));
  header.PutU32(model.segment_count);
  header.PutU32(static_cast<std::uint32_t>(model.blends.size()));
  if (masked || nodes) header.PutU32(static_cast<std::uint32_t>(model.surface_triangles.size()));
  if (nodes) header.PutU32(std::bit_cast<std::uint32_t>(model.node_spacing));
  ByteWriter body;
  // Version 3: the nodes' base vertices; a decoder derives the blends from them.
  for (std::uint32_t v : model.node_vertices) body.PutU32(v);
  for (const VertexBlend& blend : nodes ? std::span<const VertexBlend>()
                                        : std::span<const VertexBlend>(model.blends)) {
    body.PutU8(blend.count);
    for (int i = 0; i < kMaxInfluences; ++i) {
      const bool used = i < blend.count;
      body.PutU32(used ? blend.influences[i].segment : 0);
      body.PutU16(used ? static_cast<std::uint16_t>(
                             std::lround(blend.influences[i].weight * 65535.0f))
                       : 0);
    }
  }
  // The surface mask, one bit per base triangle, least significant bit first.
  std::vector<std::uint8_t> mask((model.surface_triangles.size() + 7) / 8, 0);
  for (std::size_t t = 0; t < model.surface_triangles.size(); ++t) {
    if (model.surface_triangles[t]) mask[t / 8] |= std::uint8_t(1u << (t % 8));
  }
  for (std::uint8_t byte : mask) body.PutU8(byte);
  std::vector<std::uint8_t> payload = header.Release();
  const std::vector<std::uint8_t> compressed = CompressBlock(body.bytes());
  payload.insert(payload.end(), compressed.begin(), compressed.end());
  return payload;
}

namespace {

/// EncodeTransforms with zstd at `level`.
StatusOr<EncodedTransforms> EncodeTransformsAtLevel(
    const std::vector<std::vector<RigidTransform>>& frames, const MotionQuantization& quantization,
    std::span<const Eigen::Vector3f> pivots, int level) {
  MESHVID_RETURN_IF_ERROR(CheckQuantization(quantization));
  if (frames.empty()) return InvalidArgumentError("a group of transforms needs a frame");
  const std::size_t segment_count = frames[0].size();
  if (!pivots.empty() && pivots.size() != segment_count) {
    return InvalidArgumentError("a group of transforms needs one pivot per segment or none");
  }
  ByteWriter header;
  header.PutU32(static_cast<std::uint32_t>(frames.size()));
  header.PutU32(static_cast<std::uint32_t>(segment_count));
  ByteWriter body;
  EncodedTransforms result;
  std::vector<QuantizedTransform> previous(segment_count);
  for (const auto& frame : frames) {
    if (frame.size() != segment_count) {
      return InvalidArgumentError("every frame of a group needs the same segment count");
    }
    std::vector<RigidTransform>& decoded = result.decoded.emplace_back();
    for (std::size_t s = 0; s < segment_count; ++s) {
      const QuantizedTransform q = QuantizeTransform(frame[s], quantization, PivotOf(pivots, s));
      for (int c = 0; c < 3; ++c) body.PutU32(ZigZagDelta(previous[s].rotation[c], q.rotation[c]));
      for (int c = 0; c < 3; ++c) {
        body.PutU32(ZigZagDelta(previous[s].translation[c], q.translation[c]));
      }
      previous[s] = q;
      decoded.push_back(DequantizeTransform(q, quantization));
    }
  }
  result.bytes = header.Release();
  const std::vector<std::uint8_t> compressed = CompressBlock(SplitBytePlanes(body.bytes()), level);
  result.bytes.insert(result.bytes.end(), compressed.begin(), compressed.end());
  return result;
}

}  // namespace

StatusOr<EncodedTransforms> EncodeTransforms(const std::vector<std::vector<RigidTransform>>& frames,
                                             const MotionQuantization& quantization,
                                             std::span<const Eigen::Vector3f> pivots) {
  return EncodeTransformsAtLevel(frames, quantization, pivots, /*level=*/19);
}

StatusOr<std::size_t> EstimateTransformBytes(const std::vector<std::vector<RigidTransform>>& frames,
                                             std::size_t group_size,
                                             const MotionQuantization& quantization,
                                             std::span<const Eigen::Vector3f> pivots) {
  if (group_size == 0) return InvalidArgumentError("a group holds at least one frame");
  std::size_t bytes = 0;
  for (std::size_t first = 0; first < frames.size(); first += group_size) {
    const std::vector<std::vector<RigidTransform>> group(
        frames.begin() + first, frames.begin() + std::min(frames.size(), first + group_size));
    // A faster zstd level than the files' (19): enough to tell two quantisations apart.
    MESHVID_ASSIGN_OR_RETURN(const EncodedTransforms coded,
                             EncodeTransformsAtLevel(group, quantization, pivots, /*level=*/9));
    bytes += coded.bytes.size();
  }
  return bytes;
}

}  // namespace meshvid
