// How the surface moved into the frame that ended a key group (internal to the encoder,
// deformed_key_group.cc): the next key group's key frame is that frame, and its first tracked
// frame, which has no velocity of its own, can move on as the surface moved into it.
#ifndef MESHVID_CODEC_ENC_TRACKING_MOTION_HINT_H_
#define MESHVID_CODEC_ENC_TRACKING_MOTION_HINT_H_

#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"
#include "codec/common/motion.h"

namespace meshvid {

/// How a key group's tracked surface moved into one frame.
struct MotionHint {
  int frame = -1;  ///< the frame (-1: no hint)
  /// The key group's base posed as tracked into `frame` (lost parts and all).
  std::vector<Eigen::Vector3f> positions;
  /// Per position, the step its strongest node took into `frame`: the world-space transform
  /// from where the node put the base in the frame before to where it puts it in `frame`.
  std::vector<RigidTransform> steps;
};

/// The hint of `base`, moved by `motion`, tracked with `previous` in the frame before `frame`
/// and with `tracked` in `frame`.
MotionHint HintOf(int frame, const TriangleMesh& base, const MotionModel& motion,
                  std::span<const RigidTransform> previous,
                  std::span<const RigidTransform> tracked);

/// Per deformation node of `motion` over `base` (a new key group's, whose key frame is the
/// hint's frame), the transform of the frame before the key frame that would have the node
/// move on by the step of the hint's position nearest it: constant-velocity prediction from it
/// and the key frame's identity (PredictConstantVelocity) gives that step. Empty without a hint.
std::vector<RigidTransform> StepsBefore(const MotionHint& hint, const TriangleMesh& base,
                                        const MotionModel& motion);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_TRACKING_MOTION_HINT_H_
