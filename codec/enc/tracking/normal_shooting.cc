#include "codec/enc/tracking/normal_shooting.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meshvid {
namespace {

/// Distance to the first hit along `direction` within (0, max_t] with an acceptable angle, or
/// infinity; `hit_out` receives the hit (its normal unnormalised).
float FirstHit(const EmbreeScene& scene, const Eigen::Vector3f& origin,
               const Eigen::Vector3f& direction, float max_t, float min_abs_cos, RayHit* hit_out) {
  const RayHit hit = scene.Intersect(origin, direction, 0.0f, max_t);
  if (!hit.hit()) return std::numeric_limits<float>::infinity();
  const float denominator = hit.normal.norm() * direction.norm();
  if (!(denominator > 0)) return std::numeric_limits<float>::infinity();
  const float abs_cos = std::abs(hit.normal.dot(direction)) / denominator;
  if (abs_cos < min_abs_cos) return std::numeric_limits<float>::infinity();
  *hit_out = hit;
  return hit.t;
}

/// Calls `shoot(i)` for every ray i < `count`, in parallel.
template <typename Shoot>
void ForEachRay(std::size_t count, const Shoot& shoot) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i) shoot(i);
                    });
}

}  // namespace

ShootingTarget::~ShootingTarget() = default;

StatusOr<std::unique_ptr<ShootingTarget>> ShootingTarget::Create(const TriangleMesh& mesh) {
  if (mesh.empty()) return InvalidArgumentError("cannot shoot rays at an empty mesh");
  std::unique_ptr<ShootingTarget> target(new ShootingTarget);
  MESHVID_ASSIGN_OR_RETURN(target->scene_, EmbreeScene::Create(mesh));
  target->triangle_count_ = mesh.triangle_count();
  return target;
}

ShotHit ShootingTarget::ShootHit(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                                 const ShotLimits& limits) const {
  RayHit forward_hit, backward_hit;
  const float forward =
      FirstHit(*scene_, origin, direction, limits.max_distance, limits.min_abs_cos, &forward_hit);
  const float backward =
      FirstHit(*scene_, origin, -direction, std::min(forward, limits.max_distance),
               limits.min_abs_cos, &backward_hit);
  ShotHit hit;
  if (std::isinf(forward) && std::isinf(backward)) return hit;
  const bool ahead = forward <= backward;
  const RayHit& nearest = ahead ? forward_hit : backward_hit;
  hit.distance = ahead ? forward : -backward;
  hit.normal = nearest.normal.normalized();
  hit.triangle = nearest.triangle;
  hit.u = nearest.u;
  hit.v = nearest.v;
  return hit;
}

float ShootingTarget::Shoot(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                            const ShotLimits& limits) const {
  return ShootHit(origin, direction, limits).distance;
}

void ShootingTarget::ShootAll(std::span<const Eigen::Vector3f> origins,
                              std::span<const Eigen::Vector3f> directions,
                              const ShotLimits& limits, std::vector<float>* distances) const {
  distances->resize(origins.size());
  ForEachRay(origins.size(),
             [&](std::size_t i) { (*distances)[i] = Shoot(origins[i], directions[i], limits); });
}

void ShootingTarget::ShootAllHits(std::span<const Eigen::Vector3f> origins,
                                  std::span<const Eigen::Vector3f> directions,
                                  const ShotLimits& limits, std::vector<ShotHit>* hits) const {
  hits->resize(origins.size());
  ForEachRay(origins.size(),
             [&](std::size_t i) { (*hits)[i] = ShootHit(origins[i], directions[i], limits); });
}

}  // namespace meshvid
