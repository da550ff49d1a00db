#include "codec/enc/motion_blend.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "codec/enc/segmentation.h"

namespace meshvid {
namespace {

/// Keeps the largest kMaxInfluences entries of a dense weight row, renormalised.
VertexBlend TopInfluences(std::span<const float> weights) {
  std::vector<std::uint32_t> order(weights.size());
  std::iota(order.begin(), order.end(), 0u);
  const std::size_t keep = std::min<std::size_t>(kMaxInfluences, order.size());
  std::partial_sort(order.begin(), order.begin() + keep, order.end(),
                    [&](std::uint32_t a, std::uint32_t b) { return weights[a] > weights[b]; });
  VertexBlend blend;
  float total = 0;
  for (std::size_t k = 0; k < keep && weights[order[k]] > 1e-4f; ++k) total += weights[order[k]];
  for (std::size_t k = 0; k < keep && weights[order[k]] > 1e-4f; ++k) {
    blend.influences[blend.count++] = {order[k], weights[order[k]] / total};
  }
  return blend;
}

}  // namespace

MotionModel BlendWeightsFromLabels(const BaseTopology& topology,
                                   std::span<const std::int32_t> labels, int segment_count,
                                   int smoothing, int soft_from) {
  const TriangleMesh& base = topology.mesh;
  if (soft_from < 0) soft_from = segment_count;
  const std::size_t n = base.vertex_count();
  const std::size_t s = static_cast<std::size_t>(std::max(1, segment_count));
  const auto& neighbours = topology.neighbours;
  std::vector<float> weights(n * s, 0.0f);
  std::vector<char> known(n, 0), registered(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    if (labels[v] >= 0 && labels[v] < segment_count) {
      weights[v * s + labels[v]] = 1;
      known[v] = 1;
      registered[v] = labels[v] < soft_from;
    }
  }
  // Spread outwards ring by ring: each new vertex averages its known neighbours.
  std::vector<std::size_t> frontier;
  for (;;) {
    frontier.clear();
    for (std::size_t v = 0; v < n; ++v) {
      if (known[v]) continue;
      for (std::uint32_t w : neighbours[v]) {
        if (known[w]) {
          frontier.push_back(v);
          break;
        }
      }
    }
    if (frontier.empty()) break;
    for (std::size_t v : frontier) {
      int count = 0;
      for (std::uint32_t w : neighbours[v]) {
        if (!known[w]) continue;
        for (std::size_t k = 0; k < s; ++k) weights[v * s + k] += weights[w * s + k];
        ++count;
      }
      for (std::size_t k = 0; k < s; ++k) weights[v * s + k] /= float(count);
    }
    for (std::size_t v : frontier) known[v] = 1;
  }
  // Jacobi smoothing of the interpolated weights, registered vertices fixed.
  std::vector<float> next = weights;
  for (int pass = 0; pass < smoothing; ++pass) {
    for (std::size_t v = 0; v < n; ++v) {
      if (registered[v] || !known[v] || neighbours[v].empty()) continue;
      for (std::size_t k = 0; k < s; ++k) next[v * s + k] = 0;
      int count = 0;
      for (std::uint32_t w : neighbours[v]) {
        if (!known[w]) continue;
        for (std::size_t k = 0; k < s; ++k) next[v * s + k] += weights[w * s + k];
        ++count;
      }
      for (std::size_t k = 0; k < s; ++k) next[v * s + k] /= float(std::max(count, 1));
    }
    weights.swap(next);
    next = weights;
  }
  // Pieces with no registered vertex: the nearest registered vertex's segment.
  for (std::size_t v = 0; v < n; ++v) {
    if (known[v]) continue;
    float best = std::numeric_limits<float>::infinity();
    std::int32_t segment = 0;
    for (std::size_t w = 0; w < n; ++w) {
      if (labels[w] < 0 || labels[w] >= segment_count) continue;
      const float d = (base.positions[v] - base.positions[w]).squaredNorm();
      if (d < best) best = d, segment = labels[w];
    }
    weights[v * s + segment] = 1;
  }
  MotionModel model;
  model.segment_count = static_cast<std::uint32_t>(s);
  model.blends.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    model.blends[v] = TopInfluences(std::span<const float>(weights).subspan(v * s, s));
  }
  return model;
}

std::vector<Eigen::Vector3f> PieceCentres(std::span<const Eigen::Vector3f> positions,
                                          std::span<const std::int32_t> labels, int piece_count) {
  Eigen::Vector3d all = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& p : positions) all += p.cast<double>();
  all /= double(std::max<std::size_t>(1, positions.size()));
  std::vector<Eigen::Vector3d> sums(piece_count, Eigen::Vector3d::Zero());
  std::vector<std::size_t> counts(piece_count, 0);
  for (std::size_t v = 0; v < labels.size() && v < positions.size(); ++v) {
    if (labels[v] < 0 || labels[v] >= piece_count) continue;
    sums[labels[v]] += positions[v].cast<double>();
    ++counts[labels[v]];
  }
  std::vector<Eigen::Vector3f> centres(piece_count);
  for (int s = 0; s < piece_count; ++s) {
    centres[s] = (counts[s] > 0 ? Eigen::Vector3d(sums[s] / double(counts[s])) : all).cast<float>();
  }
  return centres;
}

void SmoothTracks(int passes, std::span<const Eigen::Vector3f> centres,
                  std::vector<std::vector<RigidTransform>>* transforms) {
  const std::size_t frames = transforms->size();
  if (frames < 3) return;
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<std::vector<RigidTransform>> next = *transforms;
    for (std::size_t t = 1; t + 1 < frames; ++t) {
      for (std::size_t s = 0; s < (*transforms)[t].size(); ++s) {
        const Eigen::Vector3f c = s < centres.size() ? centres[s] : Eigen::Vector3f::Zero();
        const RigidTransform& middle = (*transforms)[t][s];
        Eigen::Vector4f q = middle.rotation.coeffs();
        Eigen::Vector3f at = middle.Apply(c);  // where the frames put the centre, summed
        for (std::size_t u : {t - 1, t + 1}) {
          const RigidTransform& other = (*transforms)[u][s];
          const Eigen::Vector4f o = other.rotation.coeffs();
          q += o.dot(middle.rotation.coeffs()) < 0 ? Eigen::Vector4f(-o) : o;
          at += other.Apply(c);
        }
        next[t][s].rotation = Eigen::Quaternionf(q.normalized());
        next[t][s].translation = at / 3.0f - next[t][s].rotation * c;
      }
    }
    transforms->swap(next);
  }
}

}  // namespace meshvid
