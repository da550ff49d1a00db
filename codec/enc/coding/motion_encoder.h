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
QuantizedTransform QuantizeTransform(const RigidTransform& transform,
                                     const MotionQuantization& quantization);

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
StatusOr<EncodedTransforms> EncodeTransforms(
    const std::vector<std::vector<RigidTransform>>& frames,
    const MotionQuantization& quantization);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_CODING_MOTION_ENCODER_H_
