// Normal shooting (docs/encoder-method.md eq. 2-3, forward mapping): from points on the base
// surface, along their normals, find the data surface in either direction, with Embree.
#ifndef MESHVID_CODEC_ENC_TRACKING_NORMAL_SHOOTING_H_
#define MESHVID_CODEC_ENC_TRACKING_NORMAL_SHOOTING_H_

#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/embree_scene.h"
#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// Limits of one shot.
struct ShotLimits {
  float max_distance = 0;  ///< farthest hit accepted, either direction (scene units)
  /// Smallest |cos| of the angle between the ray and the hit triangle's normal: rejects hits
  /// on data seen edge-on, where the mapping is not one-to-one.
  float min_abs_cos = 0.5f;
};

/// What a shot sees as a miss.
inline constexpr float kNoHit = std::numeric_limits<float>::quiet_NaN();

/// A shot's result: the signed distance along the direction (kNoHit on a miss), the unit
/// normal of the triangle hit (its sign is the triangle's winding), and where on which
/// triangle it hit (barycentric weights u, v of the triangle's corners 1 and 2).
struct ShotHit {
  float distance = kNoHit;
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
  std::uint32_t triangle = RayHit::kNone;
  float u = 0, v = 0;
  bool hit() const { return triangle != RayHit::kNone; }
};

/// An Embree scene over one triangle mesh (the views of a frame may be appended into one).
/// Shoot() may run from several threads at once.
class ShootingTarget {
 public:
  /// Builds the BVH. Fails on an empty mesh or an Embree error.
  static StatusOr<std::unique_ptr<ShootingTarget>> Create(const TriangleMesh& mesh);
  ~ShootingTarget();
  ShootingTarget(const ShootingTarget&) = delete;
  ShootingTarget& operator=(const ShootingTarget&) = delete;

  /// The signed distance t of the nearest hit origin + t * direction, |t| <= max_distance,
  /// looking forwards and backwards (direction need not be unit; t is in its units), or
  /// kNoHit.
  float Shoot(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
              const ShotLimits& limits) const;

  /// Shoot(), also returning the normal of the surface hit and where on which triangle.
  ShotHit ShootHit(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                   const ShotLimits& limits) const;

  /// Shoot() for many rays, in parallel; `distances` is resized to origins.size().
  void ShootAll(std::span<const Eigen::Vector3f> origins,
                std::span<const Eigen::Vector3f> directions, const ShotLimits& limits,
                std::vector<float>* distances) const;

  /// ShootHit() for many rays, in parallel; `hits` is resized to origins.size().
  void ShootAllHits(std::span<const Eigen::Vector3f> origins,
                    std::span<const Eigen::Vector3f> directions, const ShotLimits& limits,
                    std::vector<ShotHit>* hits) const;

  std::size_t triangle_count() const { return triangle_count_; }

 private:
  ShootingTarget() = default;
  std::unique_ptr<EmbreeScene> scene_;
  std::size_t triangle_count_ = 0;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_TRACKING_NORMAL_SHOOTING_H_
