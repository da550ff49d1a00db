#include "codec/enc/tracking/closest_point_align.h"

#include <algorithm>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

namespace meshvid {
namespace {

/// Closest-point iterations of a re-acquisition at each search radius.
constexpr int kClosestPointIterations = 15;
/// Share of the nearest closest-point pairs a re-acquisition step aligns on (trimmed ICP: the
/// part of a piece the data does not show pulls the rest towards other surfaces).
constexpr double kTrimmedShare = 0.8;

/// One step of trimmed point-to-point ICP: the members of a piece posed by `t`, paired with
/// their nearest data points within `radius`, the nearest kTrimmedShare of pairs kept; the
/// transform that best aligns them (Umeyama's closed form), or with `translate_only` `t`
/// moved by the pairs' mean offset. False when fewer than 3 pairs are found.
bool ClosestPointStep(const PointTree& tree, std::span<const Eigen::Vector3f> points,
                      std::span<const Eigen::Vector3f> positions,
                      std::span<const std::uint32_t> members, float radius, bool translate_only,
                      RigidTransform* t) {
  std::vector<std::pair<float, std::uint32_t>> pairs;  // squared distance, member index
  std::vector<std::uint32_t> nearest(members.size());
  for (std::uint32_t k = 0; k < members.size(); ++k) {
    const Eigen::Vector3f posed = t->Apply(positions[members[k]]);
    float squared = 0;
    tree.knnSearch(posed.data(), 1, &nearest[k], &squared);
    if (squared <= radius * radius) pairs.push_back({squared, k});
  }
  if (pairs.size() < 3) return false;
  std::sort(pairs.begin(), pairs.end());
  pairs.resize(std::max<std::size_t>(3, std::size_t(kTrimmedShare * double(pairs.size()))));
  Eigen::Matrix3Xf from(3, pairs.size()), to(3, pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    from.col(i) = t->Apply(positions[members[pairs[i].second]]);
    to.col(i) = points[nearest[pairs[i].second]];
  }
  if (translate_only) {
    t->translation += (to - from).rowwise().mean();
    return true;
  }
  const Eigen::Matrix4f m = Eigen::umeyama(from, to, /*with_scaling=*/false);
  if (!m.allFinite()) return false;
  RigidTransform step;
  step.rotation = Eigen::Quaternionf(Eigen::Matrix3f(m.topLeftCorner<3, 3>())).normalized();
  step.translation = m.topRightCorner<3, 1>();
  *t = Compose(step, *t);
  return true;
}

}  // namespace

RigidTransform ClosestPointAlign(const PointTree& tree, std::span<const Eigen::Vector3f> points,
                                 std::span<const Eigen::Vector3f> positions,
                                 std::span<const std::uint32_t> members, float radius,
                                 float finest, RigidTransform start) {
  RigidTransform t = start;
  for (int it = 0; it < kClosestPointIterations; ++it) {
    if (!ClosestPointStep(tree, points, positions, members, radius, true, &t)) return t;
  }
  for (float r = radius;; r = std::max(finest, r * 0.5f)) {
    for (int it = 0; it < kClosestPointIterations; ++it) {
      if (!ClosestPointStep(tree, points, positions, members, r, false, &t)) return t;
    }
    if (r <= finest) break;
  }
  return t;
}

}  // namespace meshvid
