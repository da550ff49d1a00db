#include "codec/enc/segmentation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meshvid {
namespace {

constexpr float kNoResidual = std::numeric_limits<float>::infinity();

/// a after b: x -> a(b(x)).
RigidTransform Compose(const RigidTransform& a, const RigidTransform& b) {
  RigidTransform result;
  result.rotation = (a.rotation * b.rotation).normalized();
  result.translation = a.rotation * b.translation + a.translation;
  return result;
}

RigidTransform Inverse(const RigidTransform& t) {
  RigidTransform result;
  result.rotation = t.rotation.conjugate();
  result.translation = -(result.rotation * t.translation);
  return result;
}

/// Constant-velocity prediction of frame m from frames m-1 and m-2 (the warm start of a
/// grown window; the method copies frame m-1, which fast motion outruns).
RigidTransform Predict(const std::vector<RigidTransform>& transforms, int m) {
  if (m < 1) return RigidTransform{};
  if (m < 2) return transforms[m - 1];
  const RigidTransform step = Compose(transforms[m - 1], Inverse(transforms[m - 2]));
  return Compose(step, transforms[m - 1]);
}

/// The base vertices and normals the segmentation poses.
struct BaseFrame {
  std::span<const Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
};

/// Correspondences of `members` under `transform`: the residual ||T v - c|| per member
/// (kNoResidual without a hit) and the hit points.
void Correspond(const BaseFrame& base, std::span<const std::uint32_t> members,
                const RigidTransform& transform, const ShootingTarget& target,
                const ShotLimits& limits, std::vector<float>* residuals,
                std::vector<Eigen::Vector3f>* hits, std::vector<Eigen::Vector3f>* normals) {
  residuals->resize(members.size());
  hits->resize(members.size());
  normals->resize(members.size());
  auto body = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = members[k];
      const Eigen::Vector3f origin = transform.Apply(base.positions[v]);
      const Eigen::Vector3f direction = transform.rotation * base.normals[v];
      const ShotHit hit = target.ShootHit(origin, direction, limits);
      if (std::isnan(hit.distance)) {
        (*residuals)[k] = kNoResidual;
      } else {
        (*hits)[k] = origin + hit.distance * direction;
        (*normals)[k] = hit.normal;
        (*residuals)[k] = std::abs(hit.distance);
      }
    }
  };
  if (members.size() < 256) {
    body(0, members.size());
  } else {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, members.size(), 128),
                      [&](const auto& r) { body(r.begin(), r.end()); });
  }
}

/// Weight of the point-to-point term beside the point-to-plane one in a rigid step.
constexpr double kPointWeight = 0.05;
/// Damping of a rigid step, relative to the system's mean diagonal.
constexpr double kDamping = 1e-3;

/// One Gauss-Newton step of eq. 5 for the pairs (T v_k, c_k): the point-to-plane distance
/// to the data's tangent plane at c_k (Chen & Medioni, whose normal shooting gives the
/// correspondences), plus a small point-to-point term that fixes the directions a plane
/// leaves free. Returns the updated transform; `transform` unchanged if underdetermined.
RigidTransform RigidStep(const RigidTransform& transform, std::span<const Eigen::Vector3f> from,
                         std::span<const Eigen::Vector3f> to,
                         std::span<const Eigen::Vector3f> normals) {
  if (from.size() < 3) return transform;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> posed(from.size());
  for (std::size_t k = 0; k < from.size(); ++k) {
    posed[k] = transform.Apply(from[k]).cast<double>();
    centre += posed[k];
  }
  centre /= double(from.size());
  Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
  for (std::size_t k = 0; k < from.size(); ++k) {
    const Eigen::Vector3d q = posed[k] - centre;
    const Eigen::Vector3d n = normals[k].cast<double>();
    const Eigen::Vector3d r = posed[k] - to[k].cast<double>();
    Eigen::Matrix<double, 6, 1> j;
    j << q.cross(n), n;
    a += j * j.transpose();
    b += j * n.dot(r);
    // Point term: d(q + w x q + d - c) = -[q]x w + d.
    Eigen::Matrix<double, 3, 6> jp;
    Eigen::Matrix3d skew;
    skew << 0, -q.z(), q.y(), q.z(), 0, -q.x(), -q.y(), q.x(), 0;
    jp << -skew, Eigen::Matrix3d::Identity();
    a += kPointWeight * jp.transpose() * jp;
    b += kPointWeight * jp.transpose() * r;
  }
  // Levenberg-Marquardt damping: few or nearly collinear points leave directions of the
  // system almost free; damping keeps the step there small instead of arbitrary.
  a.diagonal().array() += kDamping * a.trace() / 6.0 + 1e-12;
  const Eigen::Matrix<double, 6, 1> x = a.ldlt().solve(-b);
  if (!x.allFinite()) return transform;
  const Eigen::Vector3d w = x.head<3>(), d = x.tail<3>();
  const double angle = w.norm();
  const Eigen::Quaterniond step =
      angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle))
                : Eigen::Quaterniond::Identity();
  // x -> step (T x - centre) + centre + d
  RigidTransform result;
  result.rotation = (step.cast<float>() * transform.rotation).normalized();
  result.translation = (step * (transform.translation.cast<double>() - centre) + centre + d)
                           .cast<float>();
  return result;
}

/// Eq. 5 and 6 for one frame: from `transform`, alternately finds correspondences and solves
/// the rigid transform on those within the tolerance. With `coarse`, the tolerance first
/// halves down from the whole search distance (motion between frames can exceed the
/// method's 3 x UserTol), then shrinks from `start_factor` x options.tolerance to
/// options.tolerance by options.tolerance_shrink. Returns false if too few correspondences
/// agree at the final tolerance (the segment is unseen, or the search slid off): the caller
/// then keeps a safe transform.
bool Refine(const BaseFrame& base, std::span<const std::uint32_t> members,
            const ShootingTarget& target, const SegmentationOptions& options,
            float start_factor, bool coarse, RigidTransform* transform) {
  std::vector<float> residuals;
  std::vector<Eigen::Vector3f> hits, hit_normals, from, to, normals;
  const float fine_start = options.tolerance * std::max(1.0f, start_factor);
  float tol = fine_start;
  bool solved = false;
  if (coarse) {
    while (tol * 2 < options.shot.max_distance) tol *= 2;
  }
  for (;;) {
    for (int it = 0; it < std::max(1, options.icp_iterations); ++it) {
      Correspond(base, members, *transform, target, options.shot, &residuals, &hits,
                 &hit_normals);
      from.clear();
      to.clear();
      normals.clear();
      for (std::size_t k = 0; k < members.size(); ++k) {
        if (residuals[k] < tol) {
          from.push_back(base.positions[members[k]]);
          to.push_back(hits[k]);
          normals.push_back(hit_normals[k]);
        }
      }
      // Solved means: at the final tolerance, enough data agrees with the transform (a
      // tenth of the members: a few stray agreements are what a slid search finds).
      solved = tol <= options.tolerance &&
               from.size() >= std::max<std::size_t>(3, members.size() / 10);
      if (from.size() < 3) break;
      *transform = RigidStep(*transform, from, to, normals);
    }
    if (tol <= options.tolerance) break;
    tol = tol > fine_start ? std::max(tol * 0.5f, fine_start)
                           : std::max(tol * options.tolerance_shrink, options.tolerance);
  }
  return solved;
}

/// The largest connected piece of the vertices flagged in `member` (flags of the others are
/// cleared); returns its vertices.
std::vector<std::uint32_t> KeepLargestPiece(
    const std::vector<std::vector<std::uint32_t>>& neighbours, std::vector<char>* member) {
  const std::size_t n = member->size();
  std::vector<std::int32_t> piece(n, -1);
  std::vector<std::uint32_t> stack, best;
  std::int32_t pieces = 0;
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (!(*member)[seed] || piece[seed] >= 0) continue;
    std::vector<std::uint32_t> current;
    stack.assign(1, seed);
    piece[seed] = pieces;
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      current.push_back(v);
      for (std::uint32_t w : neighbours[v]) {
        if ((*member)[w] && piece[w] < 0) {
          piece[w] = pieces;
          stack.push_back(w);
        }
      }
    }
    if (current.size() > best.size()) best.swap(current);
    ++pieces;
  }
  std::fill(member->begin(), member->end(), 0);
  for (std::uint32_t v : best) (*member)[v] = 1;
  std::sort(best.begin(), best.end());
  return best;
}

}  // namespace

std::vector<std::vector<std::uint32_t>> VertexNeighbours(const TriangleMesh& mesh) {
  std::vector<std::vector<std::uint32_t>> neighbours(mesh.vertex_count());
  for (const Triangle& t : mesh.triangles) {
    for (int c = 0; c < 3; ++c) {
      neighbours[t[c]].push_back(t[(c + 1) % 3]);
      neighbours[t[c]].push_back(t[(c + 2) % 3]);
    }
  }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

StatusOr<Segmentation> SegmentPiecewiseRigid(const TriangleMesh& base, FrameTargets targets,
                                             const SegmentationOptions& options,
                                             const ProgressCallback& progress) {
  MESHVID_RETURN_IF_ERROR(ValidateMesh(base, "base mesh"));
  if (targets.empty()) return InvalidArgumentError("segmentation needs at least one frame");
  if (!(options.tolerance > 0)) return InvalidArgumentError("the tolerance must be positive");
  if (!(options.tolerance_shrink > 0 && options.tolerance_shrink < 1)) {
    return InvalidArgumentError("the tolerance shrink factor must be in (0, 1)");
  }
  const std::size_t n = base.vertex_count();
  const int frames = static_cast<int>(targets.size());
  const int min_size = std::max(3, options.min_segment_vertices);
  BaseFrame frame0{base.positions, ComputeVertexNormals(base)};
  const auto neighbours = VertexNeighbours(base);

  Segmentation result;
  result.labels.assign(n, kUnregistered);
  result.transforms.assign(frames, {});
  std::vector<char> unsegmented(n, 1);
  std::size_t remaining = n;
  std::vector<float> residuals;
  while (result.segment_count < options.max_segments && remaining >= std::size_t(min_size)) {
    if (!ReportProgress(progress, "segmentation", long(n - remaining), long(n))) {
      return CancelledError("segmentation cancelled");
    }
    // A new segment starts from every unsegmented vertex and shrinks as the window grows.
    std::vector<char> member = unsegmented;
    std::vector<std::uint32_t> members;
    for (std::uint32_t v = 0; v < n; ++v) {
      if (member[v]) members.push_back(v);
    }
    std::vector<int> failures(n, 0), successes(n, 0);
    std::vector<char> agreeing(n, 1);
    std::vector<std::uint32_t> solvers;
    std::vector<Eigen::Vector3f> hits, hit_normals;
    std::vector<RigidTransform> track(frames);
    bool alive = true;
    for (int m = 0; m < frames && alive; ++m) {
      track[m] = Predict(track, m);
      if (targets[m] == nullptr) continue;
      // Solve on the members that agreed when last seen: a piece that has parted from
      // the segment's motion no longer pulls the solution, even before it is dropped.
      solvers.clear();
      for (std::uint32_t v : members) {
        if (agreeing[v]) solvers.push_back(v);
      }
      if (solvers.size() < 3) solvers = members;
      // An unseen segment holds still (extrapolating its velocity would run away).
      if (!Refine(frame0, solvers, *targets[m], options, options.initial_tolerance_factor,
                  /*coarse=*/true, &track[m]) &&
          m > 0) {
        track[m] = track[m - 1];
      }
      Correspond(frame0, members, track[m], *targets[m], options.shot, &residuals, &hits,
                 &hit_normals);
      for (std::size_t k = 0; k < members.size(); ++k) {
        const std::uint32_t v = members[k];
        // A miss is an occlusion and costs nothing until the window ends; a hit outside the
        // tolerance is a disagreement.
        if (!std::isfinite(residuals[k])) continue;
        const bool agrees = residuals[k] < options.tolerance;
        ++(agrees ? successes : failures)[v];
        agreeing[v] = agrees;
      }
      // Eq. 6 may fail (data present but off) in at most occlusion_frames frames, and must
      // hold in at least one once the window is over. Occluded members still connect the
      // piece meanwhile.
      const bool last = m + 1 == frames;
      for (std::uint32_t v : members) {
        if (failures[v] > options.occlusion_frames || (last && successes[v] == 0)) {
          member[v] = 0;
        }
      }
      members = KeepLargestPiece(neighbours, &member);
      alive = members.size() >= std::size_t(min_size);
    }
    if (!alive) break;
    // Eq. 5 over the whole window again, now on the final members only.
    for (int m = 0; m < frames; ++m) {
      if (targets[m] == nullptr) continue;
      const RigidTransform before = track[m];
      if (!Refine(frame0, members, *targets[m], options, 1.0f, /*coarse=*/false, &track[m])) {
        track[m] = before;
      }
    }
    for (std::uint32_t v : members) {
      result.labels[v] = result.segment_count;
      unsegmented[v] = 0;
    }
    remaining -= members.size();
    for (int m = 0; m < frames; ++m) result.transforms[m].push_back(track[m]);
    ++result.segment_count;
  }
  if (result.segment_count == 0) {
    return InvalidArgumentError(
        "no rigid segment found: the base mesh does not match the data (fewer than " +
        std::to_string(min_size) + " connected vertices within the tolerance " +
        std::to_string(options.tolerance) + " over the frames)");
  }
  return result;
}

std::vector<RigidTransform> TrackSegments(const TriangleMesh& base,
                                          std::span<const std::int32_t> labels,
                                          int segment_count, const ShootingTarget& target,
                                          std::span<const RigidTransform> initial,
                                          const SegmentationOptions& options) {
  BaseFrame frame{base.positions, ComputeVertexNormals(base)};
  std::vector<std::vector<std::uint32_t>> members(segment_count);
  for (std::uint32_t v = 0; v < labels.size(); ++v) {
    if (labels[v] >= 0 && labels[v] < segment_count) members[labels[v]].push_back(v);
  }
  std::vector<RigidTransform> result(initial.begin(), initial.end());
  result.resize(segment_count);
  for (int s = 0; s < segment_count; ++s) {
    if (members[s].size() < 3) continue;
    if (!Refine(frame, members[s], target, options, options.initial_tolerance_factor,
                /*coarse=*/true, &result[s])) {
      result[s] = initial[s];
    }
  }
  return result;
}

}  // namespace meshvid
