// A rigid pose of a set of points found by trimmed closest-point iterations (ICP) against a
// frame's data: how a tracker searches again for a part it lost, from far away.
#ifndef MESHVID_CODEC_ENC_TRACKING_CLOSEST_POINT_ALIGN_H_
#define MESHVID_CODEC_ENC_TRACKING_CLOSEST_POINT_ALIGN_H_

#include <cstdint>
#include <span>

#include <Eigen/Core>

#include "codec/common/motion.h"
#include "codec/common/point_tree.h"

namespace meshvid {

/// The pose of `positions[members]` found by closest points over `points` (indexed by
/// `tree`) from `start`: translations alone within `radius` first (a far start would otherwise
/// turn the points to fit the part of the data they overlap), then rigid steps with the radius
/// halving down to `finest`. Each step pairs every member with its nearest point within the
/// radius and aligns on the nearest 80% of the pairs (trimmed: the part of a piece the data
/// does not show would pull the rest towards other surfaces). Stops early when fewer than 3
/// pairs are found.
RigidTransform ClosestPointAlign(const PointTree& tree, std::span<const Eigen::Vector3f> points,
                                 std::span<const Eigen::Vector3f> positions,
                                 std::span<const std::uint32_t> members, float radius,
                                 float finest, RigidTransform start);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_TRACKING_CLOSEST_POINT_ALIGN_H_
