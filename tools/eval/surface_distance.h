// Exact point-to-surface distance: the closest point on a triangle mesh, found with an
// Embree 3 BVH point query (the closest_point approach of Embree's tutorials), computed in
// double precision.
#ifndef MESHVID_TOOLS_EVAL_SURFACE_DISTANCE_H_
#define MESHVID_TOOLS_EVAL_SURFACE_DISTANCE_H_

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "codec/common/embree_scene.h"
#include "codec/common/mesh.h"
#include "codec/common/triangle_distance.h"
#include "format/status.h"

namespace meshvid {

/// Distance queries against one mesh. Build once, then query from any number of threads.
class SurfaceDistance {
 public:
  /// Builds the acceleration structure over `mesh`'s triangles (copied; the mesh need not
  /// outlive this object). Fails if the mesh has no triangles or Embree cannot start.
  static StatusOr<std::unique_ptr<SurfaceDistance>> Build(const TriangleMesh& mesh);
  ~SurfaceDistance();
  SurfaceDistance(const SurfaceDistance&) = delete;
  SurfaceDistance& operator=(const SurfaceDistance&) = delete;

  /// Euclidean distance from `point` to the closest point of the surface. Thread-safe.
  double Distance(const Eigen::Vector3f& point) const;

  /// As Distance(point), starting the search from triangle `hint_triangle` (e.g. the triangle
  /// of a nearby sample): the distance to it bounds the search, which makes it much faster.
  double DistanceFrom(const Eigen::Vector3f& point, std::uint32_t hint_triangle) const;

 private:
  SurfaceDistance() = default;
  /// The search, pruned to `radius` with `best_squared` already found; +inf if none within.
  double Search(const Eigen::Vector3f& point, double radius, double best_squared) const;
  std::unique_ptr<EmbreeScene> scene_;
  std::vector<Eigen::Vector3d> positions_;
  std::vector<Triangle> triangles_;
};

}  // namespace meshvid

#endif  // MESHVID_TOOLS_EVAL_SURFACE_DISTANCE_H_
