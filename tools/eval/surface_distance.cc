#include "tools/eval/surface_distance.h"

#include <cmath>
#include <string>

namespace meshvid {

Eigen::Vector3d ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;  // vertex region a
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;  // vertex region b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;  // edge ab
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;  // vertex region c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;  // edge ac
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {  // edge bc
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double denom = va + vb + vc;
  if (!(denom > 0.0)) return a;  // degenerate triangle: any vertex is as good (edges handled)
  const double v = vb / denom, w = vc / denom;
  return a + v * ab + w * ac;  // interior
}

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
