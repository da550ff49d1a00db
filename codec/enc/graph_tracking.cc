#include "codec/enc/graph_tracking.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <tbb/parallel_for.h>

#include "codec/common/point_tree.h"
#include "codec/enc/closest_point_align.h"
#include "codec/enc/patch_tracking.h"
#include "codec/enc/rigid_step.h"

namespace meshvid {

PieceGraph BuildPieceGraph(const BaseTopology& base, std::span<const std::int32_t> labels,
                           int fixed_count, int piece_count) {
  PieceGraph graph;
  graph.fixed_count = fixed_count;
  graph.piece_count = piece_count;
  graph.members.resize(piece_count);
  graph.adjacent.resize(piece_count);
  for (std::uint32_t v = 0; v < labels.size(); ++v) {
    if (labels[v] >= 0 && labels[v] < piece_count) graph.members[labels[v]].push_back(v);
  }
  for (const auto& members : graph.members) {
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();
    for (std::uint32_t v : members) centre += base.mesh.positions[v];
    centre /= float(std::max<std::size_t>(1, members.size()));
    double spread = 0;
    for (std::uint32_t v : members) spread += (base.mesh.positions[v] - centre).squaredNorm();
    graph.centres.push_back(centre);
    graph.radii.push_back(std::sqrt(spread / double(std::max<std::size_t>(1, members.size()))));
  }
  for (std::uint32_t u = 0; u < base.neighbours.size(); ++u) {
    for (std::uint32_t w : base.neighbours[u]) {
      if (w <= u || u >= labels.size() || w >= labels.size()) continue;
      const std::int32_t a = labels[u], b = labels[w];
      if (a < 0 || b < 0 || a >= piece_count || b >= piece_count || a == b) continue;
      if (a < fixed_count && b < fixed_count) continue;
      graph.seams.push_back({u, w, a, b});
      for (auto [p, q] : {std::pair{a, b}, std::pair{b, a}}) {
        auto& list = graph.adjacent[p];
        if (std::find(list.begin(), list.end(), q) == list.end()) list.push_back(q);
      }
    }
  }
  return graph;
}

int SplitIntoNodes(const BaseTopology& base, int piece_count, int node_vertices, int max_pieces,
                   std::vector<std::int32_t>* labels, std::vector<std::int32_t>* parents) {
  parents->resize(piece_count);
  for (int p = 0; p < piece_count; ++p) (*parents)[p] = p;
  if (node_vertices < 3) return piece_count;
  std::vector<std::size_t> sizes(piece_count, 0);
  for (std::int32_t l : *labels) {
    if (l >= 0 && l < piece_count) ++sizes[l];
  }
  std::vector<int> order(piece_count);
  for (int p = 0; p < piece_count; ++p) order[p] = p;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return sizes[a] > sizes[b]; });
  int count = piece_count;
  std::vector<std::int32_t> alone(labels->size());
  for (int p : order) {
    if (sizes[p] <= std::size_t(node_vertices) || count >= max_pieces) break;
    // The piece's vertices are the only unregistered ones; its nodes are labelled count...
    for (std::size_t v = 0; v < alone.size(); ++v) alone[v] = (*labels)[v] == p ? -1 : 0;
    PatchTrackingOptions split;
    split.patch_vertices = node_vertices;
    split.max_segments = max_pieces + 1;  // the first node returns to the piece's label
    const int end = PartitionUnregistered(base, count, 3, split, &alone);
    if (end <= count + 1) continue;
    for (std::size_t v = 0; v < alone.size(); ++v) {
      if ((*labels)[v] != p) continue;
      const std::int32_t node = alone[v];
      if (node > count) (*labels)[v] = node - 1;  // else: the first node, or a scrap: stays p
    }
    for (int k = count; k < end - 1; ++k) parents->push_back(p);
    count = end - 1;
  }
  return count;
}

void JointStep(const BaseTopology& base, const PieceGraph& graph, const ShootingTarget& target,
               const JointStepSettings& settings, std::vector<RigidTransform>* transforms) {
  const int fixed = graph.fixed_count;
  const int free = graph.piece_count - fixed;
  if (free <= 0) return;
  const auto& positions = base.mesh.positions;
  std::vector<Eigen::Vector3d> centres(free);
  for (int p = 0; p < free; ++p) {
    centres[p] = (*transforms)[fixed + p].Apply(graph.centres[fixed + p]).cast<double>();
  }
  const double sigma = settings.robust_scale * settings.tolerance;
  // Per free piece: its 6x6 block and right-hand side from its data.
  std::vector<Matrix6d> diagonal(free, Matrix6d::Zero());
  std::vector<Vector6d> rhs(free, Vector6d::Zero());
  tbb::parallel_for(0, free, [&](int p) {
    const RigidTransform& t = (*transforms)[fixed + p];
    const auto& members = graph.members[fixed + p];
    for (std::uint32_t v : members) {
      const Eigen::Vector3f origin = t.Apply(positions[v]);
      const Eigen::Vector3f direction = t.rotation * base.normals[v];
      const ShotHit hit = target.ShootHit(origin, direction, settings.shot);
      if (std::isnan(hit.distance) || std::abs(hit.distance) >= settings.tolerance) continue;
      const Eigen::Vector3d x = origin.cast<double>();
      const Eigen::Vector3d r = x - (origin + hit.distance * direction).cast<double>();
      const Eigen::Vector3d n = hit.normal.cast<double>();
      // Geman-McClure's weight of the point-to-plane residual.
      const double plane = n.dot(r);
      const double weight =
          sigma > 0 ? std::pow(sigma * sigma / (sigma * sigma + plane * plane), 2) : 1.0;
      AddCorrespondence(x - centres[p], n, r, &diagonal[p], &rhs[p], weight);
    }
    Vector6d prior;
    const double r2 = graph.radii[fixed + p] * graph.radii[fixed + p];
    prior << r2, r2, r2, 1, 1, 1;
    diagonal[p].diagonal() += settings.prior_weight * double(members.size()) * prior;
  });
  // Seams: the two pieces should put each seam vertex at the same place.
  std::vector<Eigen::Triplet<double>> triplets;
  const double w = settings.stiffness;
  using Jacobian = Eigen::Matrix<double, 3, 6>;
  for (const PieceSeam& seam : graph.seams) {
    const RigidTransform& ta = (*transforms)[seam.a];
    const RigidTransform& tb = (*transforms)[seam.b];
    const int pa = seam.a - fixed, pb = seam.b - fixed;  // negative: a fixed piece
    for (std::uint32_t v : {seam.u, seam.w}) {
      const Eigen::Vector3d xa = ta.Apply(positions[v]).cast<double>();
      const Eigen::Vector3d xb = tb.Apply(positions[v]).cast<double>();
      const Eigen::Vector3d r = xa - xb;
      // The residual xa - xb: + the point's derivative for a, - for b.
      const Jacobian ja = pa >= 0 ? PointJacobian(xa - centres[pa]) : Jacobian::Zero();
      const Jacobian jb = pb >= 0 ? Jacobian(-PointJacobian(xb - centres[pb])) : Jacobian::Zero();
      if (pa >= 0) {
        diagonal[pa] += w * ja.transpose() * ja;
        rhs[pa] += w * ja.transpose() * r;
      }
      if (pb >= 0) {
        diagonal[pb] += w * jb.transpose() * jb;
        rhs[pb] += w * jb.transpose() * r;
      }
      if (pa >= 0 && pb >= 0) {
        const Matrix6d off = w * ja.transpose() * jb;
        for (int i = 0; i < 6; ++i) {
          for (int k = 0; k < 6; ++k) {
            triplets.emplace_back(6 * pa + i, 6 * pb + k, off(i, k));
            triplets.emplace_back(6 * pb + k, 6 * pa + i, off(i, k));
          }
        }
      }
    }
  }
  Eigen::VectorXd b(6 * free);
  for (int p = 0; p < free; ++p) {
    DampRigidBlock(&diagonal[p]);
    for (int i = 0; i < 6; ++i) {
      for (int k = 0; k < 6; ++k) triplets.emplace_back(6 * p + i, 6 * p + k, diagonal[p](i, k));
    }
    b.segment<6>(6 * p) = -rhs[p];
  }
  Eigen::SparseMatrix<double> a(6 * free, 6 * free);
  a.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
  if (solver.info() != Eigen::Success) return;
  const Eigen::VectorXd x = solver.solve(b);
  if (!x.allFinite()) return;
  for (int p = 0; p < free; ++p) {
    RigidTransform& t = (*transforms)[fixed + p];
    t = ApplyIncrement(t, x.segment<6>(6 * p), centres[p]);
  }
}

void SolveJointly(const BaseTopology& base, const PieceGraph& graph, const ShootingTarget& target,
                  const SegmentationOptions& seg, JointStepSettings settings, bool fine_only,
                  std::vector<RigidTransform>* transforms) {
  const float fine_start = seg.tolerance * std::max(1.0f, seg.initial_tolerance_factor);
  float tol = fine_start;
  while (!fine_only && tol * 2 < seg.shot.max_distance) tol *= 2;
  for (;;) {
    settings.tolerance = tol;
    for (int it = 0; it < std::max(1, seg.icp_iterations); ++it) {
      JointStep(base, graph, target, settings, transforms);
    }
    if (tol <= seg.tolerance) break;
    tol = tol > fine_start ? std::max(tol * 0.5f, fine_start)
                           : std::max(tol * seg.tolerance_shrink, seg.tolerance);
  }
}

GraphTracker::GraphTracker(const BaseTopology& base, std::span<const std::int32_t> labels,
                           int piece_count, const SegmentationOptions& seg,
                           const GraphTrackingOptions& options, int fixed_count)
    : base_(base),
      seg_(seg),
      options_(options),
      graph_(BuildPieceGraph(base, labels, fixed_count, piece_count)) {}

int GraphTracker::Agreeing(int piece, const ShootingTarget& target,
                           const RigidTransform& transform) const {
  ShotLimits limits = seg_.shot;
  limits.max_distance = seg_.tolerance;
  int agree = 0;
  for (std::uint32_t v : graph_.members[piece]) {
    const float d = target.Shoot(transform.Apply(base_.mesh.positions[v]),
                                 transform.rotation * base_.normals[v], limits);
    agree += !std::isnan(d);
  }
  return agree;
}

bool GraphTracker::Reacquire(int piece, const ShootingTarget& target,
                             std::span<const RigidTransform> previous,
                             std::vector<RigidTransform> aligned,
                             const std::vector<int>& agreeing,
                             std::vector<RigidTransform>* transforms) const {
  const auto& members = graph_.members[piece];
  const double size = double(members.size());
  // Start poses: the last frame's (the motion reversed), carried by each well-supported
  // neighbour (a limb moves with the body), and the closest-point alignments.
  std::vector<RigidTransform> starts = std::move(aligned);
  starts.push_back(previous[piece]);
  for (std::int32_t q : graph_.adjacent[piece]) {
    if (agreeing[q] < options_.reacquire_below * double(graph_.members[q].size())) continue;
    starts.push_back(
        Compose(Compose((*transforms)[q], Inverse(previous[q])), previous[piece]));
  }
  int best = agreeing[piece];
  std::optional<RigidTransform> found;
  for (RigidTransform start : starts) {
    const int agree = SolveSegment(base_, members, target, seg_, &start);
    if (agree > best) best = agree, found = start;
  }
  if (!found || best < agreeing[piece] + options_.reacquire_gain * size ||
      best < options_.reacquire_below * size) {
    return false;
  }
  (*transforms)[piece] = *found;
  return true;
}

std::vector<RigidTransform> GraphTracker::Track(const ShootingTarget& target,
                                                std::span<const Eigen::Vector3f> points,
                                                std::span<const RigidTransform> previous,
                                                std::span<const RigidTransform> before,
                                                std::span<const RigidTransform> fixed,
                                                GraphTrackStats* stats) const {
  const int pieces = graph_.piece_count;
  std::vector<RigidTransform> transforms(pieces);
  for (int p = 0; p < pieces; ++p) {
    transforms[p] = p < graph_.fixed_count ? fixed[p]
                    : before.size() == previous.size()
                        ? PredictConstantVelocity(before[p], previous[p])
                        : previous[p];
  }
  JointStepSettings settings;
  settings.shot = seg_.shot;
  settings.stiffness = options_.stiffness;
  settings.robust_scale = options_.robust_scale;
  settings.prior_weight = options_.prior_weight;
  SolveJointly(base_, graph_, target, seg_, settings, /*fine_only=*/false, &transforms);
  std::vector<int> agreeing(pieces);
  tbb::parallel_for(0, pieces, [&](int p) { agreeing[p] = Agreeing(p, target, transforms[p]); });
  GraphTrackStats local;
  std::unique_ptr<PointTree> tree;  // over the frame's points, built when first needed
  const PointCloud cloud{points};
  for (int p = graph_.fixed_count; p < pieces; ++p) {
    const auto& members = graph_.members[p];
    const double size = double(members.size());
    if (size < std::max(3, options_.reacquire_min_vertices) ||
        agreeing[p] >= options_.reacquire_below * size) {
      continue;
    }
    ++local.searched;
    // Closest points over the whole frame, within a widening radius.
    std::vector<RigidTransform> aligned;
    if (!points.empty()) {
      if (!tree) {
        tree = std::make_unique<PointTree>(
            3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
      }
      const float widest = std::max(options_.reacquire_max_distance, seg_.shot.max_distance);
      for (float radius = 2 * seg_.shot.max_distance;; radius *= 2) {
        radius = std::min(radius, widest);
        aligned.push_back(ClosestPointAlign(*tree, points, base_.mesh.positions, members, radius,
                                            seg_.shot.max_distance, transforms[p]));
        if (radius >= widest) break;
      }
    }
    local.reacquired += Reacquire(p, target, previous, std::move(aligned), agreeing, &transforms);
  }
  if (local.reacquired > 0) {
    SolveJointly(base_, graph_, target, seg_, settings, /*fine_only=*/true, &transforms);
  }
  if (stats != nullptr) *stats = local;
  return transforms;
}

}  // namespace meshvid
