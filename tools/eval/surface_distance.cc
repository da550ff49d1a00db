#include "tools/eval/surface_distance.h"

#include <cmath>
#include <string>

namespace meshvid {

namespace {

/// The state one point query carries through the scene's triangle visits.
struct QueryState {
  const std::vector<Eigen::Vector3d>* positions;
  const std::vector<Triangle>* triangles;
  Eigen::Vector3d point;
  double best_squared;
};

bool VisitTriangle(void* user, std::uint32_t triangle, float* radius) {
  auto* state = static_cast<QueryState*>(user);
  const Triangle& tri = (*state->triangles)[triangle];
  const auto& pos = *state->positions;
  // The distance to the triangle's plane is a lower bound: skip triangles it rules out.
  const Eigen::Vector3d normal = (pos[tri[1]] - pos[tri[0]]).cross(pos[tri[2]] - pos[tri[0]]);
  const double normal_squared = normal.squaredNorm();
  if (normal_squared > 0.0) {
    const double plane = normal.dot(state->point - pos[tri[0]]);
    if (plane * plane >= state->best_squared * normal_squared) return false;
  }
  const Eigen::Vector3d q =
      ClosestPointOnTriangle(state->point, pos[tri[0]], pos[tri[1]], pos[tri[2]]);
  const double squared = (q - state->point).squaredNorm();
  if (squared < state->best_squared) {
    state->best_squared = squared;
    // Shrink the search sphere, rounding up so float rounding cannot cut a tie away.
    *radius = std::nextafter(static_cast<float>(std::sqrt(squared)), INFINITY);
    return true;
  }
  return false;
}

}  // namespace

StatusOr<std::unique_ptr<SurfaceDistance>> SurfaceDistance::Build(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) {
    return InvalidArgumentError("cannot measure distances to a mesh with no triangles");
  }
  std::unique_ptr<SurfaceDistance> result(new SurfaceDistance());
  MESHVID_ASSIGN_OR_RETURN(result->scene_, EmbreeScene::Create(mesh));
  result->positions_.reserve(mesh.positions.size());
  for (const Eigen::Vector3f& p : mesh.positions) result->positions_.push_back(p.cast<double>());
  result->triangles_ = mesh.triangles;
  return result;
}

SurfaceDistance::~SurfaceDistance() = default;

double SurfaceDistance::Distance(const Eigen::Vector3f& point) const {
  return Search(point, std::numeric_limits<double>::infinity(),
                std::numeric_limits<double>::infinity());
}

double SurfaceDistance::DistanceFrom(const Eigen::Vector3f& point,
                                     std::uint32_t hint_triangle) const {
  const Triangle& tri = triangles_[hint_triangle];
  const Eigen::Vector3d p = point.cast<double>();
  const double squared =
      (ClosestPointOnTriangle(p, positions_[tri[0]], positions_[tri[1]], positions_[tri[2]]) - p)
          .squaredNorm();
  const double distance = std::sqrt(squared);
  // A small margin keeps the bound safe against float rounding in the BVH.
  const double margin = 1e-6 * (point.cwiseAbs().maxCoeff() + distance) + 1e-30;
  return Search(point, distance * (1.0 + 1e-5) + margin, squared);
}

double SurfaceDistance::Search(const Eigen::Vector3f& point, double radius,
                               double best_squared) const {
  QueryState state{&positions_, &triangles_, point.cast<double>(), best_squared};
  scene_->VisitTrianglesNear(point, static_cast<float>(radius), VisitTriangle, &state);
  return std::sqrt(state.best_squared);
}

}  // namespace meshvid
