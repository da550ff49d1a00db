// Encoding of the motion streams: MOTN (segments, blend weights, quantisation steps) and the
// per-group transform payloads, quantised, predicted from the previous frame, split into byte
// planes, zstd-coded.
#ifndef MESHVID_CODEC_ENC_CODING_MOTION_ENCODER_H_
#define MESHVID_CODEC_ENC_CODING_MOTION_ENCODER_H_

#include <cstdint>
#include <span>
#include <vector>

#include "codec/common/motion.h"
#include "codec/dec/motion_decoder.h"
#include "format/status.h"

namespace meshvid {

/// The nearest quantised transform (rotation vector and translation rounded to the steps).
/// The translation is the one that, with the rounded rotation, moves `pivot` where `transform`
/// does: the rotation's rounding then displaces a point by its distance from the pivot times
/// the rotation error, not by its distance from the origin (MotionPivots).
QuantizedTransform QuantizeTransform(const RigidTransform& transform,
                                     const MotionQuantization& quantization,
                                     const Eigen::Vector3f& pivot = Eigen::Vector3f::Zero());

/// The point each segment's transforms are quantised about, and how far from it the segment
/// reaches.
struct MotionPivots {
  std::vector<Eigen::Vector3f> pivots;  ///< per segment: the centre of its vertices' bounding box
  /// The largest distance from a segment's pivot to a vertex it moves, over all segments.
  float reach = 0;
};

/// Segment `segment`'s pivot in `pivots`, or the origin where `pivots` has none (empty: every
/// segment rounded about the origin).
inline Eigen::Vector3f PivotOf(std::span<const Eigen::Vector3f> pivots, std::size_t segment) {
  return segment < pivots.size() ? pivots[segment] : Eigen::Vector3f(Eigen::Vector3f::Zero());
}

/// The pivots of `model`'s segments over base positions `positions` (one per blend). A
/// segment that moves no vertex gets the origin.
MotionPivots FindMotionPivots(const MotionModel& model, std::span<const Eigen::Vector3f> positions);

/// The rotation step whose rounding moves no vertex of a segment reaching `reach` from its
/// pivot by more than a quarter of what a translation step's does (below 0.5 radian, and never
/// finer than `quantization`'s own).
float RotationStepForReach(const MotionQuantization& quantization, float reach);

/// MOTN payload for `model`; weights are stored in 1/65535 steps, the last influence of a
/// vertex taking the remainder. Fails if the model is invalid or a step is not positive.
StatusOr<std::vector<std::uint8_t>> EncodeMotionModel(const MotionModel& model,
                                                      const MotionQuantization& quantization);

/// A coded group of transforms and what a decoder will reconstruct from it.
struct EncodedTransforms {
  std::vector<std::uint8_t> bytes;
  std::vector<std::vector<RigidTransform>> decoded;  ///< [frame][segment], de-quantised
};

/// Codes `frames[frame][segment]`; every frame must have the same number of segments.
/// The first frame of the group is coded from zero, so every group decodes on its own. The
/// deltas are written as byte planes (TransformByteOrder::kBytePlanes, side_info_version 2).
/// `pivots` (one per segment, or empty: the origin) are those of QuantizeTransform.
StatusOr<EncodedTransforms> EncodeTransforms(const std::vector<std::vector<RigidTransform>>& frames,
                                             const MotionQuantization& quantization,
                                             std::span<const Eigen::Vector3f> pivots = {});

/// About the bytes EncodeTransforms gives `frames` (a key group's track) coded in groups of
/// `group_size` frames: to choose between quantisations without coding at the files' level.
StatusOr<std::size_t> EstimateTransformBytes(const std::vector<std::vector<RigidTransform>>& frames,
                                             std::size_t group_size,
                                             const MotionQuantization& quantization,
                                             std::span<const Eigen::Vector3f> pivots = {});

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_CODING_MOTION_ENCODER_H_
