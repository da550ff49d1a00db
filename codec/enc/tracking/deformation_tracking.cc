#include "codec/enc/tracking/deformation_tracking.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <tbb/parallel_for.h>

#include "codec/common/deformation_graph.h"
#include "codec/common/point_tree.h"
#include "codec/enc/tracking/closest_point_align.h"

namespace meshvid {
namespace {

/// Per node, the number of its piece: nodes joined through `adjacent` share one.
std::vector<int> NodePieces(const std::vector<std::vector<std::int32_t>>& adjacent) {
  std::vector<int> piece(adjacent.size(), -1);
  int pieces = 0;
  std::vector<std::size_t> stack;
  for (std::size_t start = 0; start < adjacent.size(); ++start) {
    if (piece[start] >= 0) continue;
    piece[start] = pieces;
    stack.assign(1, start);
    while (!stack.empty()) {
      const std::size_t a = stack.back();
      stack.pop_back();
      for (std::int32_t b : adjacent[a]) {
        if (piece[b] < 0) {
          piece[b] = pieces;
          stack.push_back(b);
        }
      }
    }
    ++pieces;
  }
  return piece;
}

/// Holds every node to the nearest node of another piece within `reach` (among its
/// kJoinCandidates nearest nodes), both ways.
void JoinSeparatePieces(std::span<const Eigen::Vector3f> node_positions, float reach,
                        std::vector<std::vector<std::int32_t>>* adjacent) {
  constexpr std::size_t kJoinCandidates = 16;
  const std::vector<int> piece = NodePieces(*adjacent);
  const PointCloud cloud{node_positions};
  const PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
  const float reach_squared = reach * reach;
  std::vector<std::pair<std::int32_t, std::int32_t>> joins;
  for (std::size_t a = 0; a < node_positions.size(); ++a) {
    std::array<std::uint32_t, kJoinCandidates> nearest;
    std::array<float, kJoinCandidates> squared;
    const std::size_t found =
        tree.knnSearch(node_positions[a].data(), kJoinCandidates, nearest.data(), squared.data());
    for (std::size_t k = 0; k < found && squared[k] <= reach_squared; ++k) {
      if (piece[nearest[k]] != piece[a]) {
        joins.emplace_back(static_cast<std::int32_t>(a), static_cast<std::int32_t>(nearest[k]));
        break;
      }
    }
  }
  for (const auto& [a, b] : joins) {
    (*adjacent)[a].push_back(b);
    (*adjacent)[b].push_back(a);
  }
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

/// A lost part is also searched for turned about its joint by +-1..kTurnSteps times
/// kTurnDegrees about each axis.
constexpr int kTurnSteps = 2;
constexpr float kTurnDegrees = 20;

/// The Gauss-Newton solve of one frame's node transforms (DeformationTracker::Track).
class FrameSolver {
 public:
  FrameSolver(const BaseTopology& base, const DeformationGraph& graph,
              const DeformationTrackingOptions& options, const TrackingData& frame,
              std::span<const RigidTransform> previous, double rigidity)
      : base_(base),
        graph_(graph),
        options_(options),
        frame_(frame),
        cloud_{frame.points},
        tree_(3, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize)),
        rigidity_(rigidity),
        match_(base.mesh.vertex_count()) {
    // The rigidity holds the shape the last frame had, not the key frame's (a limb bent away
    // from its rest pose is not pulled back straight).
    HoldShapeOf(previous);
    IndexBlocks();
    // Correspondence radii halving from the search distance to 2 tolerances.
    for (float r = options.max_distance; r > 2.5f * options.tolerance; r *= 0.5f) {
      radii_.push_back(r);
    }
    radii_.push_back(2 * options.tolerance);
  }

  /// Makes the rigidity hold the nodes to the shape `shape` gives them: where node j puts
  /// node k, in node j's rest coordinates.
  void HoldShapeOf(std::span<const RigidTransform> shape) {
    const auto& rest = base_.mesh.positions;
    anchors_.assign(graph_.node_count(), {});
    for (std::size_t j = 0; j < anchors_.size(); ++j) {
      const RigidTransform inverse = Inverse(shape[j]);
      for (std::int32_t k : graph_.adjacent[j]) {
        anchors_[j].push_back(
            inverse.Apply(shape[k].Apply(rest[graph_.motion.node_vertices[k]])).cast<double>());
      }
    }
  }

  /// Gauss-Newton from `transforms`, `iterations` steps per radius, coarse to fine, the
  /// rigidity `coarse_stiffness` times stiffer at the first radius (the first call also
  /// decides which way the data's normals face, from its start); with `finest_only`, at the
  /// two finest radii alone.
  std::vector<RigidTransform> Solve(std::vector<RigidTransform> transforms, int iterations,
                                    double coarse_stiffness = 1, bool finest_only = false) {
    if (!facing_known_) {
      facing_ = DataFacing(transforms);
      facing_known_ = true;
    }
    // Stiff at the coarse radii, where the nearest data may belong to another part, relaxing
    // geometrically to the set rigidity at the last radius (non-rigid ICP's decreasing
    // stiffness): a fast part first moves as a whole, then bends.
    const double coarse = std::max(1.0, coarse_stiffness);
    const std::size_t first = finest_only && radii_.size() > 2 ? radii_.size() - 2 : 0;
    for (std::size_t r = first; r < radii_.size(); ++r) {
      const double stiffness =
          radii_.size() > 1 ? std::pow(coarse, double(radii_.size() - 1 - r) /
                                                   double(radii_.size() - 1))
                            : 1.0;
      for (int iteration = 0; iteration < iterations; ++iteration) {
        if (Correspond(transforms, radii_[r]) == 0 ||
            !Step(stiffness * rigidity_, &transforms)) {
          break;
        }
      }
    }
    return transforms;
  }

  /// How many vertices posed by `transforms` have data within the last radius.
  std::size_t Matched(const std::vector<RigidTransform>& transforms) {
    return Correspond(transforms, radii_.back());
  }

  /// Searches again for the parts the solve lost (DeformationTrackingOptions::
  /// reacquire_max_distance) and moves each found one's nodes there; returns how many moved.
  int Reacquire(std::vector<RigidTransform>* transforms) {
    const float finest = radii_.back();
    Correspond(*transforms, finest);
    const std::size_t nodes = graph_.node_count();
    std::vector<std::vector<std::uint32_t>> nearest(nodes);  // per node, the vertices nearest
    for (std::uint32_t v = 0; v < match_.size(); ++v) {
      nearest[graph_.motion.blends[v].influences[0].segment].push_back(v);
    }
    auto supported = [&](std::span<const std::uint32_t> vertices) {
      return static_cast<std::size_t>(std::count_if(
          vertices.begin(), vertices.end(), [&](std::uint32_t v) { return match_[v] >= 0; }));
    };
    std::vector<char> lost(nodes, 0);
    for (std::size_t j = 0; j < nodes; ++j) {
      lost[j] = !nearest[j].empty() && double(supported(nearest[j])) <
                                           options_.reacquire_below * double(nearest[j].size());
    }
    const float widest = std::max(options_.reacquire_max_distance, options_.max_distance);
    int moved = 0;
    std::vector<char> seen(nodes, 0);
    for (std::size_t seed = 0; seed < nodes; ++seed) {
      if (!lost[seed] || seen[seed]) continue;
      // The connected part of lost nodes around `seed`, and the vertices nearest to them.
      std::vector<std::uint32_t> part{static_cast<std::uint32_t>(seed)}, members;
      seen[seed] = 1;
      for (std::size_t i = 0; i < part.size(); ++i) {
        members.insert(members.end(), nearest[part[i]].begin(), nearest[part[i]].end());
        for (const std::int32_t k : graph_.adjacent[part[i]]) {
          if (lost[k] && !seen[k]) seen[k] = 1, part.push_back(static_cast<std::uint32_t>(k));
        }
      }
      const double size = double(members.size());
      if (members.size() < std::size_t(std::max(3, options_.reacquire_min_vertices))) continue;
      const std::size_t before = supported(members);
      std::size_t best = before;
      std::optional<RigidTransform> found;
      // Aligned from `start` within `radius`; kept when more of the part lands on data.
      auto try_from = [&](const RigidTransform& start, float radius) {
        const RigidTransform aligned =
            ClosestPointAlign(tree_, frame_.points, posed_, members, radius, finest, start);
        const std::size_t agree = Supported(aligned, members, finest);
        if (agree > best) best = agree, found = aligned;
      };
      for (float radius = 2 * options_.max_distance;; radius *= 2) {
        radius = std::min(radius, widest);
        try_from(RigidTransform{}, radius);
        if (radius >= widest) break;
      }
      // Turned about where the part hangs on the rest (the found nodes beside it; its centre
      // when it hangs on nothing): a limb swings about its joint.
      Eigen::Vector3f pivot = Eigen::Vector3f::Zero();
      int pivots = 0;
      for (const std::uint32_t j : part) {
        for (const std::int32_t k : graph_.adjacent[j]) {
          if (!lost[k]) pivot += posed_[graph_.motion.node_vertices[k]], ++pivots;
        }
      }
      if (pivots == 0) {
        for (const std::uint32_t v : members) pivot += posed_[v];
        pivots = static_cast<int>(members.size());
      }
      pivot /= float(pivots);
      for (int axis = 0; axis < 3; ++axis) {
        for (int step = -kTurnSteps; step <= kTurnSteps; ++step) {
          if (step == 0) continue;
          RigidTransform turned;
          turned.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(
              float(step * kTurnDegrees * M_PI / 180), Eigen::Vector3f::Unit(axis)));
          turned.translation = pivot - turned.rotation * pivot;
          try_from(turned, options_.max_distance);
        }
      }
      if (!found || double(best) < double(before) + options_.reacquire_gain * size ||
          double(best) < options_.reacquire_below * size) {
        continue;
      }
      for (const std::uint32_t j : part) (*transforms)[j] = Compose(*found, (*transforms)[j]);
      ++moved;
    }
    return moved;
  }

 private:
  /// +1 when the data's normals face the way the base's do, -1 when most nearest points within
  /// the search distance disagree (a capture may wind its views the other way round).
  float DataFacing(std::span<const RigidTransform> transforms) {
    PoseVertices(graph_.motion, transforms, base_.mesh.positions, &posed_);
    ComputeVertexNormals(posed_, base_.mesh.triangles, &normals_);
    long vote = 0;
    for (std::size_t v = 0; v < posed_.size(); ++v) {
      std::uint32_t index = 0;
      float squared = 0;
      if (tree_.knnSearch(posed_[v].data(), 1, &index, &squared) == 1 &&
          squared <= options_.max_distance * options_.max_distance) {
        const float cosine = frame_.normals[index].dot(normals_[v]);
        vote += cosine >= options_.min_normal_cos ? 1 : cosine <= -options_.min_normal_cos ? -1 : 0;
      }
    }
    return vote < 0 ? -1.0f : 1.0f;
  }

  /// Poses the base and finds every vertex's correspondence (match_, -1: none): the nearest
  /// data point within `radius` whose normal agrees. Returns how many vertices have one.
  std::size_t Correspond(const std::vector<RigidTransform>& transforms, float radius) {
    PoseVertices(graph_.motion, transforms, base_.mesh.positions, &posed_);
    ComputeVertexNormals(posed_, base_.mesh.triangles, &normals_);
    tbb::parallel_for(std::size_t(0), posed_.size(), [&](std::size_t v) {
      match_[v] = AgreeingDataPoint(posed_[v], normals_[v], radius);
    });
    return static_cast<std::size_t>(
        std::count_if(match_.begin(), match_.end(), [](std::int32_t m) { return m >= 0; }));
  }

  /// How many of `members`, posed as the last Correspond() left them and moved by `move`, have
  /// a data point within `radius` whose normal agrees.
  std::size_t Supported(const RigidTransform& move, std::span<const std::uint32_t> members,
                        float radius) const {
    return static_cast<std::size_t>(
        std::count_if(members.begin(), members.end(), [&](std::uint32_t v) {
          return AgreeingDataPoint(move.Apply(posed_[v]), move.rotation * normals_[v], radius) >=
                 0;
        }));
  }

  /// The nearest data point within `radius` of `at` whose normal agrees with `normal` (among
  /// the nearest few), or -1.
  std::int32_t AgreeingDataPoint(const Eigen::Vector3f& at, const Eigen::Vector3f& normal,
                                 float radius) const {
    constexpr int kCandidates = 8;
    std::uint32_t index[kCandidates];
    float squared[kCandidates];
    const std::size_t found = tree_.knnSearch(at.data(), kCandidates, index, squared);
    for (std::size_t k = 0; k < found && squared[k] <= radius * radius; ++k) {
      if (facing_ * frame_.normals[index[k]].dot(normal) >= options_.min_normal_cos) {
        return static_cast<std::int32_t>(index[k]);
      }
    }
    return -1;
  }

  /// The index of the normal equations' 6x6 block of nodes (a, b), added if new.
  std::int32_t BlockOf(std::uint32_t a, std::uint32_t b,
                       std::unordered_map<std::uint64_t, std::int32_t>* index) {
    const std::uint64_t key = (std::uint64_t{a} << 32) | b;
    const auto next = static_cast<std::int32_t>(block_nodes_.size());
    const auto [at, added] = index->try_emplace(key, next);
    if (added) block_nodes_.emplace_back(a, b);
    return at->second;
  }

  /// Finds the blocks of the normal equations that can be non-zero, once per frame: the node
  /// pairs that blend a vertex together and the neighbours held together. Step() then sums
  /// into them instead of making 36 triplets per pair per vertex, and the sparse pattern is
  /// the same at every step, so it is ordered once.
  void IndexBlocks() {
    std::unordered_map<std::uint64_t, std::int32_t> index;
    const std::size_t n = base_.mesh.vertex_count();
    vertex_blocks_.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
      const VertexBlend& blend = graph_.motion.blends[v];
      for (int a = 0; a < blend.count; ++a) {
        for (int b = 0; b < blend.count; ++b) {
          vertex_blocks_[v][a * kMaxInfluences + b] =
              BlockOf(blend.influences[a].segment, blend.influences[b].segment, &index);
        }
      }
    }
    edge_blocks_.resize(graph_.node_count());
    for (std::uint32_t j = 0; j < graph_.node_count(); ++j) {
      for (const std::int32_t k : graph_.adjacent[j]) {
        const auto other = static_cast<std::uint32_t>(k);
        edge_blocks_[j].push_back({BlockOf(j, j, &index), BlockOf(j, other, &index),
                                   BlockOf(other, j, &index), BlockOf(other, other, &index)});
      }
    }
    for (std::uint32_t j = 0; j < graph_.node_count(); ++j) BlockOf(j, j, &index);
    sums_.resize(block_nodes_.size());
  }

  /// Adds J^T M J and -J^T M r for a residual r with metric M and blocks of J per node;
  /// `block_of(a, b)` is the index of the normal equations' block of which[a], which[b].
  template <typename BlockIndex>
  void Add(std::span<const std::int32_t> which, std::span<const Eigen::Matrix<double, 3, 6>> blocks,
           const BlockIndex& block_of, const Eigen::Matrix3d& metric,
           const Eigen::Vector3d& residual) {
    for (std::size_t a = 0; a < which.size(); ++a) {
      const Eigen::Matrix<double, 6, 3> jt_m = blocks[a].transpose() * metric;
      rhs_.segment<6>(6 * which[a]) -= jt_m * residual;
      for (std::size_t b = 0; b < which.size(); ++b) {
        sums_[block_of(a, b)].noalias() += jt_m * blocks[b];
      }
    }
  }

  /// One Gauss-Newton step over the correspondences of the last Correspond(), neighbours held
  /// together with weight `rigidity`; false when the system cannot be solved (the transforms
  /// are then left as they were).
  bool Step(double rigidity, std::vector<RigidTransform>* transforms) {
    const auto& rest = base_.mesh.positions;
    const std::size_t nodes = graph_.node_count();
    const int unknowns = static_cast<int>(6 * nodes);
    // Each node's posed centre c: a step turns its points y about it,
    // y' = y + w x (y - c) + t (linearised in the node's turn w and shift t).
    std::vector<Eigen::Vector3d> centres(nodes);
    std::vector<Eigen::Matrix3d> rotations(nodes);
    for (std::size_t j = 0; j < nodes; ++j) {
      rotations[j] = (*transforms)[j].rotation.toRotationMatrix().cast<double>();
      centres[j] = rotations[j] * rest[graph_.motion.node_vertices[j]].cast<double>() +
                   (*transforms)[j].translation.cast<double>();
    }
    for (auto& sum : sums_) sum.setZero();
    rhs_ = Eigen::VectorXd::Zero(unknowns);
    std::array<std::int32_t, kMaxInfluences> which{};
    std::array<Eigen::Matrix<double, 3, 6>, kMaxInfluences> blocks;
    // Data: point-to-plane and a little point-to-point to each vertex's correspondence.
    for (std::size_t v = 0; v < rest.size(); ++v) {
      if (match_[v] < 0) continue;
      const Eigen::Vector3d p = rest[v].cast<double>();
      const Eigen::Vector3d target = frame_.points[match_[v]].cast<double>();
      const Eigen::Vector3d nd = frame_.normals[match_[v]].cast<double>();
      const VertexBlend& blend = graph_.motion.blends[v];
      for (int k = 0; k < blend.count; ++k) {
        const std::uint32_t j = blend.influences[k].segment;
        const double w = blend.influences[k].weight;
        const Eigen::Vector3d y = rotations[j] * p + (*transforms)[j].translation.cast<double>();
        which[k] = static_cast<std::int32_t>(j);
        blocks[k].leftCols<3>() = -w * Skew(y - centres[j]);
        blocks[k].rightCols<3>() = w * Eigen::Matrix3d::Identity();
      }
      const Eigen::Matrix3d metric =
          nd * nd.transpose() + options_.point_weight * Eigen::Matrix3d::Identity();
      const auto& vertex_blocks = vertex_blocks_[v];
      Add(std::span(which).first(blend.count), std::span(blocks).first(blend.count),
          [&](std::size_t a, std::size_t b) { return vertex_blocks[a * kMaxInfluences + b]; },
          metric, posed_[v].cast<double>() - target);
    }
    // Rigidity: node j puts node k where it did in the previous frame, relative to itself.
    for (std::size_t j = 0; j < nodes; ++j) {
      for (std::size_t e = 0; e < graph_.adjacent[j].size(); ++e) {
        const std::int32_t k = graph_.adjacent[j][e];
        const Eigen::Vector3d y =
            rotations[j] * anchors_[j][e] + (*transforms)[j].translation.cast<double>();
        which[0] = static_cast<std::int32_t>(j);
        which[1] = k;
        blocks[0].leftCols<3>() = -Skew(y - centres[j]);
        blocks[0].rightCols<3>() = Eigen::Matrix3d::Identity();
        blocks[1].leftCols<3>().setZero();
        blocks[1].rightCols<3>() = -Eigen::Matrix3d::Identity();
        const auto& edge_blocks = edge_blocks_[j][e];
        Add(std::span(which).first(2), std::span(blocks).first(2),
            [&](std::size_t a, std::size_t b) { return edge_blocks[2 * a + b]; },
            rigidity * Eigen::Matrix3d::Identity(), y - centres[k]);
      }
    }
    // Damping: a node neither data nor neighbours decide stays where it is.
    const double damping = 1e-6 * rigidity;
    triplets_.clear();
    for (std::size_t i = 0; i < sums_.size(); ++i) {
      const auto [a, b] = block_nodes_[i];
      for (int r = 0; r < 6; ++r) {
        for (int c = 0; c < 6; ++c) {
          const double diagonal = a == b && r == c ? damping : 0.0;
          triplets_.emplace_back(6 * a + r, 6 * b + c, sums_[i](r, c) + diagonal);
        }
      }
    }
    Eigen::SparseMatrix<double> system(unknowns, unknowns);
    system.setFromTriplets(triplets_.begin(), triplets_.end());
    if (!ordered_) {
      solver_.analyzePattern(system);
      ordered_ = true;
    }
    solver_.factorize(system);
    if (solver_.info() != Eigen::Success) return false;
    const Eigen::VectorXd step = solver_.solve(rhs_);
    if (solver_.info() != Eigen::Success || !step.allFinite()) return false;
    for (std::size_t j = 0; j < nodes; ++j) {
      const Eigen::Vector3d omega = step.segment<3>(6 * j);
      const Eigen::Vector3d tau = step.segment<3>(6 * j + 3);
      const double angle = omega.norm();
      const Eigen::Quaterniond turn =
          angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega / angle))
                    : Eigen::Quaterniond::Identity();
      RigidTransform& t = (*transforms)[j];
      const Eigen::Vector3d translation = t.translation.cast<double>();
      t.rotation = (turn.cast<float>() * t.rotation).normalized();
      t.translation = (turn * (translation - centres[j]) + centres[j] + tau).cast<float>();
    }
    return true;
  }

  const BaseTopology& base_;
  const DeformationGraph& graph_;
  const DeformationTrackingOptions& options_;
  const TrackingData& frame_;
  const PointCloud cloud_;
  const PointTree tree_;
  const double rigidity_;
  std::vector<std::vector<Eigen::Vector3d>> anchors_;  ///< per node, per edge
  std::vector<float> radii_;
  float facing_ = 1;
  bool facing_known_ = false;
  std::vector<Eigen::Vector3f> posed_, normals_;
  std::vector<std::int32_t> match_;
  /// The normal equations' blocks that can be non-zero (IndexBlocks): their nodes (row,
  /// column) and sums; per vertex, the block of its influences a, b at a * kMaxInfluences + b;
  /// per node and edge, the blocks (j, j), (j, k), (k, j), (k, k).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> block_nodes_;
  std::vector<Eigen::Matrix<double, 6, 6>> sums_;
  std::vector<std::array<std::int32_t, kMaxInfluences * kMaxInfluences>> vertex_blocks_;
  std::vector<std::vector<std::array<std::int32_t, 4>>> edge_blocks_;
  std::vector<Eigen::Triplet<double>> triplets_;
  Eigen::VectorXd rhs_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
  bool ordered_ = false;  ///< solver_ has the pattern's ordering
};

}  // namespace

StatusOr<DeformationGraph> BuildDeformationGraph(const BaseTopology& base, float node_spacing,
                                                 float join_distance) {
  DeformationGraph graph;
  MESHVID_ASSIGN_OR_RETURN(graph.motion,
                           SampleNodeMotion(base.mesh, base.neighbours, node_spacing));
  const MotionModel& motion = graph.motion;
  // Nodes that blend a vertex together, and nodes nearest to the two ends of an edge (a node whose
  // vertices lie farther than its reach from other nodes, on a long sliver, is not left free), are
  // held together.
  graph.adjacent.assign(graph.node_count(), {});
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
  if (join_distance > 0) {
    std::vector<Eigen::Vector3f> node_positions;
    node_positions.reserve(graph.node_count());
    for (std::uint32_t v : motion.node_vertices) node_positions.push_back(base.mesh.positions[v]);
    JoinSeparatePieces(node_positions, join_distance, &graph.adjacent);
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
    std::span<const RigidTransform> before, DeformationTrackStats* stats) const {
  if (stats != nullptr) *stats = DeformationTrackStats{};
  const std::size_t nodes = graph_.node_count();
  std::vector<RigidTransform> predicted(previous.begin(), previous.end());
  if (before.size() != previous.size()) before = {};
  for (std::size_t j = 0; j < nodes && !before.empty(); ++j) {
    predicted[j] = PredictConstantVelocity(before[j], previous[j]);
  }
  if (frame.points.empty() || nodes == 0) return predicted;
  FrameSolver solver(base_, graph_, options_, frame, previous, options_.rigidity * edge_weight_);
  std::vector<RigidTransform> best;
  if (before.empty()) {
    // Without a velocity (the key group's second frame), from the last pose with more steps
    // and stiff at first: the whole frame's motion is left to the solve.
    best = solver.Solve(std::move(predicted), options_.first_iterations,
                        options_.coarse_stiffness);
  } else {
    // From the constant-velocity prediction and from the last pose (a part that stops or
    // turns back is found from where it was): the pose more of the base's vertices find data
    // near (within the last radius) is kept.
    best = solver.Solve(predicted, options_.iterations);
    std::vector<RigidTransform> held = solver.Solve(
        std::vector<RigidTransform>(previous.begin(), previous.end()), options_.iterations);
    if (solver.Matched(held) > solver.Matched(best)) best = std::move(held);
  }
  if (options_.reacquire_max_distance > 0) {
    std::vector<RigidTransform> moved = best;
    const int parts = solver.Reacquire(&moved);
    if (parts > 0) {
      // Held to the shape the found parts give it: the last frame's would pull them back.
      solver.HoldShapeOf(moved);
      moved = solver.Solve(std::move(moved), options_.iterations, 1, /*finest_only=*/true);
      if (solver.Matched(moved) > solver.Matched(best)) {
        best = std::move(moved);
        if (stats != nullptr) stats->reacquired = parts;
      }
    }
  }
  return best;
}

}  // namespace meshvid
