#include "codec/enc/tracking/rigid_node_groups.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <set>
#include <tuple>

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace meshvid {
namespace {

/// Weighted sums over a set of vertices of their rest positions p and posed positions x in one
/// frame: enough to fit the rigid transform mapping p to x and to measure any transform's
/// residual.
struct PairSums {
  double count = 0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), x = Eigen::Vector3d::Zero();
  Eigen::Matrix3d xp = Eigen::Matrix3d::Zero();  ///< sum of x p^T
  double pp = 0, xx = 0;                         ///< sums of |p|^2 and |x|^2

  void Add(const Eigen::Vector3d& rest, const Eigen::Vector3d& posed, double weight) {
    count += weight;
    p += weight * rest;
    x += weight * posed;
    xp += weight * posed * rest.transpose();
    pp += weight * rest.squaredNorm();
    xx += weight * posed.squaredNorm();
  }
  PairSums& operator+=(const PairSums& o) {
    count += o.count;
    p += o.p;
    x += o.x;
    xp += o.xp;
    pp += o.pp;
    xx += o.xx;
    return *this;
  }

  /// The least-squares rigid transform x = R p + t (Kabsch), identity without vertices. Fitted
  /// from the sums, not the points (as Eigen::umeyama, the encoder's other rigid fit, needs):
  /// two groups' sums add when they are joined.
  std::pair<Eigen::Matrix3d, Eigen::Vector3d> Fit() const {
    if (count == 0) return {Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()};
    const Eigen::Vector3d p_mean = p / count, x_mean = x / count;
    const Eigen::Matrix3d centred = xp - count * x_mean * p_mean.transpose();
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(centred,
                                                Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
    if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) d(2, 2) = -1;
    const Eigen::Matrix3d r = svd.matrixU() * d * svd.matrixV().transpose();
    return {r, x_mean - r * p_mean};
  }

  /// Weighted sum of |R p + t - x|^2 over the vertices.
  double Residual(const Eigen::Matrix3d& r, const Eigen::Vector3d& t) const {
    const double sum = pp + xx + count * t.squaredNorm() + 2 * t.dot(r * p) - 2 * t.dot(x) -
                       2 * (r.cwiseProduct(xp)).sum();
    return std::max(0.0, sum);
  }
};

/// Per node and frame, the sums over the vertices it moves, each where the node's own
/// transform puts it and weighted by its influence: a group's transform replaces the node's on
/// all of them, not just near the node.
std::vector<std::vector<PairSums>> SumsByNodeAndFrame(
    std::span<const Eigen::Vector3f> rest, const MotionModel& motion,
    std::span<const std::vector<RigidTransform>> tracks) {
  const std::size_t nodes = motion.segment_count, frames = tracks.size();
  std::vector<std::vector<PairSums>> node_sums(nodes, std::vector<PairSums>(frames));
  for (std::size_t v = 0; v < rest.size() && v < motion.blends.size(); ++v) {
    const VertexBlend& blend = motion.blends[v];
    for (int k = 0; k < blend.count; ++k) {
      const BlendInfluence& influence = blend.influences[k];
      if (influence.segment >= nodes) continue;
      for (std::size_t f = 0; f < frames; ++f) {
        if (influence.segment >= tracks[f].size()) continue;
        node_sums[influence.segment][f].Add(
            rest[v].cast<double>(), tracks[f][influence.segment].Apply(rest[v]).cast<double>(),
            influence.weight);
      }
    }
  }
  return node_sums;
}

/// Numbers the groups still alive (by their first node) 0, 1, ... and fits each group of more
/// than one node its transform per frame from its sums.
void NumberGroups(const std::vector<std::vector<std::uint32_t>>& members,
                  const std::vector<char>& alive,
                  const std::vector<std::vector<PairSums>>& group_sums,
                  std::span<const std::vector<RigidTransform>> tracks, RigidNodeGroups* groups) {
  const std::size_t frames = tracks.size();
  groups->transforms.assign(frames, std::vector<RigidTransform>(groups->group_count));
  int next = 0;
  for (std::uint32_t g = 0; g < members.size(); ++g) {
    if (!alive[g]) continue;
    for (const std::uint32_t j : members[g]) groups->group_of_node[j] = next;
    for (std::size_t f = 0; f < frames && members[g].size() > 1; ++f) {
      RigidTransform& fitted = groups->transforms[f][next];
      if (group_sums[g][f].count == 0) {  // its nodes move no vertex
        if (members[g][0] < tracks[f].size()) fitted = tracks[f][members[g][0]];
        continue;
      }
      const auto [r, t] = group_sums[g][f].Fit();
      fitted.rotation = Eigen::Quaternionf(r.cast<float>()).normalized();
      fitted.translation = t.cast<float>();
    }
    ++next;
  }
}

}  // namespace

RigidNodeGroups FindRigidNodeGroups(std::span<const Eigen::Vector3f> rest,
                                    const MotionModel& motion,
                                    std::span<const std::vector<std::int32_t>> adjacent,
                                    std::span<const std::vector<RigidTransform>> tracks,
                                    float tolerance) {
  const std::size_t nodes = motion.segment_count;
  RigidNodeGroups groups;
  groups.group_of_node.resize(nodes);
  for (std::size_t j = 0; j < nodes; ++j) groups.group_of_node[j] = static_cast<std::int32_t>(j);
  groups.group_count = static_cast<int>(nodes);
  const std::size_t frames = tracks.size();
  if (nodes < 2 || frames == 0 || adjacent.size() != nodes) return groups;

  const std::vector<std::vector<PairSums>> node_sums = SumsByNodeAndFrame(rest, motion, tracks);

  // Groups by the id of their first node: members, sums per frame, neighbours, version.
  std::vector<std::vector<std::uint32_t>> members(nodes);
  std::vector<std::vector<PairSums>> group_sums = node_sums;
  std::vector<std::set<std::uint32_t>> neighbours(nodes);
  std::vector<int> version(nodes, 0);
  for (std::uint32_t j = 0; j < nodes; ++j) {
    members[j] = {j};
    for (const std::int32_t k : adjacent[j]) {
      if (k >= 0 && std::size_t(k) < nodes && std::uint32_t(k) != j) neighbours[j].insert(k);
    }
  }
  for (std::uint32_t j = 0; j < nodes; ++j) {
    for (const std::uint32_t k : neighbours[j]) neighbours[k].insert(j);  // symmetric
  }
  const double limit = double(tolerance);
  // Over the nodes of a and b and the frames, the worst RMS distance between one transform
  // per frame fitted to both and each node's own, on the vertices the node moves (once above
  // the limit, no more is measured).
  auto cost = [&](std::uint32_t a, std::uint32_t b) {
    double worst = 0;
    for (std::size_t f = 0; f < frames && worst <= limit; ++f) {
      PairSums both = group_sums[a][f];
      both += group_sums[b][f];
      const auto [r, t] = both.Fit();
      for (const std::uint32_t group : {a, b}) {
        for (const std::uint32_t j : members[group]) {
          const PairSums& s = node_sums[j][f];
          if (s.count == 0) continue;
          worst = std::max(worst, std::sqrt(s.Residual(r, t) / s.count));
        }
      }
    }
    return worst;
  };
  using Candidate = std::tuple<double, std::uint32_t, std::uint32_t, int, int>;
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> queue;
  auto push = [&](std::uint32_t a, std::uint32_t b) {
    const double c = cost(a, b);
    if (c <= limit) queue.emplace(c, a, b, version[a], version[b]);
  };
  for (std::uint32_t j = 0; j < nodes; ++j) {
    for (const std::uint32_t k : neighbours[j]) {
      if (j < k) push(j, k);
    }
  }
  std::vector<char> alive(nodes, 1);
  while (!queue.empty()) {
    const auto [cost_ab, a, b, version_a, version_b] = queue.top();
    queue.pop();
    if (!alive[a] || !alive[b] || version[a] != version_a || version[b] != version_b) continue;
    // b joins a.
    members[a].insert(members[a].end(), members[b].begin(), members[b].end());
    for (std::size_t f = 0; f < frames; ++f) group_sums[a][f] += group_sums[b][f];
    for (const std::uint32_t k : neighbours[b]) {
      neighbours[k].erase(b);
      if (k != a) {
        neighbours[k].insert(a);
        neighbours[a].insert(k);
      }
    }
    neighbours[a].erase(b);
    neighbours[b].clear();
    alive[b] = 0;
    ++version[a];
    --groups.group_count;
    for (const std::uint32_t k : neighbours[a]) push(std::min(a, k), std::max(a, k));
  }
  NumberGroups(members, alive, group_sums, tracks, &groups);
  return groups;
}

void ApplyRigidNodeGroups(const RigidNodeGroups& groups,
                          std::vector<std::vector<RigidTransform>>* tracks) {
  const std::size_t nodes = groups.group_of_node.size();
  std::vector<int> size(groups.group_count, 0);
  for (const std::int32_t g : groups.group_of_node) ++size[g];
  for (std::size_t f = 0; f < tracks->size() && f < groups.transforms.size(); ++f) {
    std::vector<RigidTransform>& frame = (*tracks)[f];
    if (frame.size() != nodes) continue;
    for (std::size_t j = 0; j < nodes; ++j) {
      const std::int32_t g = groups.group_of_node[j];
      if (size[g] > 1) frame[j] = groups.transforms[f][g];
    }
  }
}

}  // namespace meshvid
