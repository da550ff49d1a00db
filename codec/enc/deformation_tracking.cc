#include "codec/enc/deformation_tracking.h"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "codec/common/deformation_graph.h"
#include "codec/common/point_tree.h"

namespace meshvid {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

}  // namespace

StatusOr<DeformationGraph> BuildDeformationGraph(const BaseTopology& base, float node_spacing) {
  DeformationGraph graph;
  graph.node_vertices = SampleDeformationNodes(base.mesh, base.neighbours, node_spacing);
  MotionModel& motion = graph.motion;
  motion.segment_count = static_cast<std::uint32_t>(graph.node_vertices.size());
  motion.node_vertices = graph.node_vertices;
  motion.node_spacing = node_spacing;
  MESHVID_ASSIGN_OR_RETURN(motion.blends, DeriveNodeBlends(base.mesh, base.neighbours,
                                                           graph.node_vertices, node_spacing));
  // Nodes that blend a vertex together, and nodes nearest to the two ends of an edge (a node whose
  // vertices lie farther than its reach from other nodes, on a long sliver, is not left free), are
  // held together.
  graph.adjacent.assign(graph.node_vertices.size(), {});
  const std::size_t n = base.mesh.vertex_count();
  for (std::uint32_t v = 0; v < n; ++v) {
    const VertexBlend& blend = motion.blends[v];
    for (int a = 0; a < blend.count; ++a) {
      for (int b = 0; b < blend.count; ++b) {
        if (a != b) {
          graph.adjacent[blend.influences[a].segment].push_back(blend.influences[b].segment);
        }
      }
    }
    for (std::uint32_t w : base.neighbours[v]) {
      const std::uint32_t nearest_v = blend.influences[0].segment;
      const std::uint32_t nearest_w = motion.blends[w].influences[0].segment;
      if (nearest_v != nearest_w) graph.adjacent[nearest_v].push_back(nearest_w);
    }
  }
  for (auto& list : graph.adjacent) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return graph;
}

DeformationTracker::DeformationTracker(const BaseTopology& base, const DeformationGraph& graph,
                                       const DeformationTrackingOptions& options)
    : base_(base), graph_(graph), options_(options) {
  std::size_t edges = 0;
  for (const auto& list : graph.adjacent) edges += list.size();
  // A node's edges together weigh as much as the data of the vertices it carries.
  edge_weight_ = double(base.mesh.vertex_count()) / double(std::max<std::size_t>(1, edges));
}

std::vector<RigidTransform> DeformationTracker::Track(
    const TrackingData& frame, std::span<const RigidTransform> previous,
    std::span<const RigidTransform> before) const {
  const std::size_t nodes = graph_.node_vertices.size();
  std::vector<RigidTransform> predicted(previous.begin(), previous.end());
  if (before.size() != previous.size()) before = {};
  for (std::size_t j = 0; j < nodes && !before.empty(); ++j) {
    predicted[j] = PredictConstantVelocity(before[j], previous[j]);
  }
  if (frame.points.empty() || nodes == 0) return predicted;
  const PointCloud cloud{frame.points};
  const PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));

  const auto& rest = base_.mesh.positions;
  const std::size_t n = rest.size();
  const int unknowns = static_cast<int>(6 * nodes);
  std::vector<Eigen::Vector3f> posed, normals;
  std::vector<std::int32_t> match(n);
  constexpr int kCandidates = 8;

  // Where node j put node k in the previous frame, in node j's rest coordinates: the rigidity holds
  // the shape the last frame had, not the key frame's (a limb bent away from its rest pose is not
  // pulled back straight).
  std::vector<std::vector<Eigen::Vector3d>> anchors(nodes);
  for (std::size_t j = 0; j < nodes; ++j) {
    const RigidTransform inverse = Inverse(previous[j]);
    for (std::int32_t k : graph_.adjacent[j]) {
      anchors[j].push_back(
          inverse.Apply(previous[k].Apply(rest[graph_.node_vertices[k]])).cast<double>());
    }
  }
  // Correspondence radii halving from the search distance to 2 tolerances.
  std::vector<float> radii;
  for (float r = options_.max_distance; r > 2.5f * options_.tolerance; r *= 0.5f) {
    radii.push_back(r);
  }
  radii.push_back(2 * options_.tolerance);
  const double rigidity = options_.rigidity * edge_weight_;
  // Whether the data's normals face the way the base's do (a capture may wind its views the
  // other way round): the sign most nearest points within the search distance agree on.
  float facing = 1;
  {
    PoseVertices(graph_.motion, predicted, rest, &posed);
    ComputeVertexNormals(posed, base_.mesh.triangles, &normals);
    long vote = 0;
    for (std::size_t v = 0; v < n; ++v) {
      std::uint32_t index = 0;
      float squared = 0;
      if (tree.knnSearch(posed[v].data(), 1, &index, &squared) == 1 &&
          squared <= options_.max_distance * options_.max_distance) {
        const float cosine = frame.normals[index].dot(normals[v]);
        vote += cosine >= options_.min_normal_cos ? 1 : cosine <= -options_.min_normal_cos ? -1 : 0;
      }
    }
    if (vote < 0) facing = -1;
  }
  // Poses the base and finds every vertex's correspondence (`match`, -1: none): the nearest data
  // point within `radius` whose normal agrees. Returns how many vertices have one.
  auto correspond = [&](const std::vector<RigidTransform>& transforms, float radius) {
    PoseVertices(graph_.motion, transforms, rest, &posed);
    ComputeVertexNormals(posed, base_.mesh.triangles, &normals);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) {
      match[v] = -1;
      std::uint32_t index[kCandidates];
      float squared[kCandidates];
      const std::size_t found = tree.knnSearch(posed[v].data(), kCandidates, index, squared);
      for (std::size_t k = 0; k < found; ++k) {
        if (squared[k] > radius * radius) break;
        const Eigen::Vector3f& nd = frame.normals[index[k]];
        if (facing * nd.dot(normals[v]) >= options_.min_normal_cos) {
          match[v] = static_cast<std::int32_t>(index[k]);
          break;
        }
      }
    });
    return static_cast<std::size_t>(
        std::count_if(match.begin(), match.end(), [](std::int32_t m) { return m >= 0; }));
  };
  // Gauss-Newton from `transforms`, coarse to fine.
  auto solve = [&](std::vector<RigidTransform> transforms) {
    for (const float radius : radii) {
      for (int iteration = 0; iteration < options_.iterations; ++iteration) {
        correspond(transforms, radius);
        // Each node's posed centre c: a step turns its points y about it,
        // y' = y + w x (y - c) + t (linearised in the node's turn w and shift t).
        std::vector<Eigen::Vector3d> centres(nodes);
        std::vector<Eigen::Matrix3d> rotations(nodes);
        for (std::size_t j = 0; j < nodes; ++j) {
          rotations[j] = transforms[j].rotation.toRotationMatrix().cast<double>();
          centres[j] = rotations[j] * rest[graph_.node_vertices[j]].cast<double>() +
                       transforms[j].translation.cast<double>();
        }
        std::vector<Eigen::Triplet<double>> triplets;
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(unknowns);
        // Adds J^T M J and -J^T M r for a residual r with metric M and blocks of J per node.
        auto add = [&](const std::array<std::int32_t, 2 * kMaxInfluences>& which,
                       const std::array<Eigen::Matrix<double, 3, 6>, 2 * kMaxInfluences>& blocks,
                       int count, const Eigen::Matrix3d& metric, const Eigen::Vector3d& residual) {
          for (int a = 0; a < count; ++a) {
            const Eigen::Matrix<double, 6, 3> jt_m = blocks[a].transpose() * metric;
            rhs.segment<6>(6 * which[a]) -= jt_m * residual;
            for (int b = 0; b < count; ++b) {
              const Eigen::Matrix<double, 6, 6> h = jt_m * blocks[b];
              for (int r = 0; r < 6; ++r) {
                for (int c = 0; c < 6; ++c) {
                  triplets.emplace_back(6 * which[a] + r, 6 * which[b] + c, h(r, c));
                }
              }
            }
          }
        };
        std::array<std::int32_t, 2 * kMaxInfluences> which{};
        std::array<Eigen::Matrix<double, 3, 6>, 2 * kMaxInfluences> blocks;
        std::size_t matched = 0;
        for (std::size_t v = 0; v < n; ++v) {
          if (match[v] < 0) continue;
          ++matched;
          const Eigen::Vector3d p = rest[v].cast<double>();
          const Eigen::Vector3d target = frame.points[match[v]].cast<double>();
          const Eigen::Vector3d nd = frame.normals[match[v]].cast<double>();
          const VertexBlend& blend = graph_.motion.blends[v];
          for (int k = 0; k < blend.count; ++k) {
            const std::uint32_t j = blend.influences[k].segment;
            const double w = blend.influences[k].weight;
            const Eigen::Vector3d y = rotations[j] * p + transforms[j].translation.cast<double>();
            which[k] = static_cast<std::int32_t>(j);
            blocks[k].leftCols<3>() = -w * Skew(y - centres[j]);
            blocks[k].rightCols<3>() = w * Eigen::Matrix3d::Identity();
          }
          const Eigen::Vector3d residual = posed[v].cast<double>() - target;
          const Eigen::Matrix3d metric =
              nd * nd.transpose() + options_.point_weight * Eigen::Matrix3d::Identity();
          add(which, blocks, blend.count, metric, residual);
        }
        // Rigidity: node j puts node k where node k puts itself.
        for (std::size_t j = 0; j < nodes; ++j) {
          for (std::size_t e = 0; e < graph_.adjacent[j].size(); ++e) {
            const std::int32_t k = graph_.adjacent[j][e];
            const Eigen::Vector3d g = anchors[j][e];
            const Eigen::Vector3d y = rotations[j] * g + transforms[j].translation.cast<double>();
            which[0] = static_cast<std::int32_t>(j);
            which[1] = k;
            blocks[0].leftCols<3>() = -Skew(y - centres[j]);
            blocks[0].rightCols<3>() = Eigen::Matrix3d::Identity();
            blocks[1].leftCols<3>().setZero();
            blocks[1].rightCols<3>() = -Eigen::Matrix3d::Identity();
            add(which, blocks, 2, rigidity * Eigen::Matrix3d::Identity(), y - centres[k]);
          }
        }
        if (matched == 0) break;
        // Damping: a node neither data nor neighbours decide stays where it is.
        const double damping = 1e-6 * rigidity;
        for (int i = 0; i < unknowns; ++i) triplets.emplace_back(i, i, damping);
        Eigen::SparseMatrix<double> system(unknowns, unknowns);
        system.setFromTriplets(triplets.begin(), triplets.end());
        const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(system);
        if (solver.info() != Eigen::Success) break;
        const Eigen::VectorXd step = solver.solve(rhs);
        if (solver.info() != Eigen::Success || !step.allFinite()) break;
        for (std::size_t j = 0; j < nodes; ++j) {
          const Eigen::Vector3d omega = step.segment<3>(6 * j);
          const Eigen::Vector3d tau = step.segment<3>(6 * j + 3);
          const double angle = omega.norm();
          const Eigen::Quaterniond turn =
              angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega / angle))
                        : Eigen::Quaterniond::Identity();
          const Eigen::Vector3d t = transforms[j].translation.cast<double>();
          transforms[j].rotation = (turn.cast<float>() * transforms[j].rotation).normalized();
          transforms[j].translation = (turn * (t - centres[j]) + centres[j] + tau).cast<float>();
        }
      }
    }
    return transforms;
  };
  // From the constant-velocity prediction and, where it differs, from the last pose (a part that
  // stops or turns back is found from where it was): the pose more of the base's vertices find data
  // near (within the last radius) is kept.
  std::vector<RigidTransform> best = solve(predicted);
  if (!before.empty()) {
    std::vector<RigidTransform> held =
        solve(std::vector<RigidTransform>(previous.begin(), previous.end()));
    if (correspond(held, radii.back()) > correspond(best, radii.back())) best = std::move(held);
  }
  return best;
}

}  // namespace meshvid
