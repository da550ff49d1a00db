#include "codec/common/deformation_graph.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <utility>

namespace meshvid {
namespace {

/// A node reaching a vertex along the edges.
struct Reach {
  float distance = 0;
  std::uint32_t node = 0;
  bool operator<(const Reach& other) const {
    return distance < other.distance || (distance == other.distance && node < other.node);
  }
};

/// Most reaches per vertex, on average, before a graph is refused as unbounded work (a
/// sampled graph has about 30 on a flat surface: nodes a spacing apart within 3 spacings).
constexpr std::size_t kMaxReachesPerVertex = 128;

/// Shortest distances along the edges from `source`, up to `radius`: calls visit(v, d) once
/// per vertex reached, nearest first. `distance` is all infinite on entry and on return.
template <class Visit>
void SpreadAlongEdges(const TriangleMesh& mesh,
                      const std::vector<std::vector<std::uint32_t>>& neighbours,
                      std::uint32_t source, float radius, std::vector<float>* distance,
                      std::vector<std::uint32_t>* touched, Visit visit) {
  using Entry = std::pair<float, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  constexpr float kFar = std::numeric_limits<float>::infinity();
  (*distance)[source] = 0;
  touched->push_back(source);
  queue.push({0.0f, source});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > (*distance)[v]) continue;
    visit(v, d);
    for (std::uint32_t w : neighbours[v]) {
      const float next = d + (mesh.positions[w] - mesh.positions[v]).norm();
      if (!(next <= radius) || next >= (*distance)[w]) continue;
      if ((*distance)[w] == kFar) touched->push_back(w);
      (*distance)[w] = next;
      queue.push({next, w});
    }
  }
  for (std::uint32_t v : *touched) (*distance)[v] = kFar;
  touched->clear();
}

}  // namespace

std::vector<std::uint32_t> SampleDeformationNodes(
    const TriangleMesh& mesh, const std::vector<std::vector<std::uint32_t>>& neighbours,
    float spacing) {
  const std::size_t n = mesh.vertex_count();
  std::vector<float> distance(n, std::numeric_limits<float>::infinity());
  std::vector<std::uint32_t> touched;
  std::vector<char> covered(n, 0);
  std::vector<std::uint32_t> nodes;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (covered[v]) continue;
    nodes.push_back(v);
    SpreadAlongEdges(mesh, neighbours, v, spacing, &distance, &touched,
                     [&](std::uint32_t w, float) { covered[w] = 1; });
  }
  return nodes;
}

StatusOr<std::vector<VertexBlend>> DeriveNodeBlends(
    const TriangleMesh& mesh, const std::vector<std::vector<std::uint32_t>>& neighbours,
    std::span<const std::uint32_t> node_vertices, float spacing) {
  const std::size_t n = mesh.vertex_count();
  if (!(spacing > 0) || !std::isfinite(spacing)) {
    return CorruptError("deformation graph: node spacing " + std::to_string(spacing) +
                        " is not positive and finite");
  }
  if (node_vertices.empty() || node_vertices.size() > n) {
    return CorruptError("deformation graph: " + std::to_string(node_vertices.size()) +
                        " nodes for " + std::to_string(n) + " vertices");
  }
  std::vector<char> is_node(n, 0);
  for (std::uint32_t v : node_vertices) {
    if (v >= n || is_node[v]) {
      return CorruptError("deformation graph: node vertex " + std::to_string(v) +
                          (v >= n ? " is out of range" : " is repeated"));
    }
    is_node[v] = 1;
  }
  std::vector<std::vector<Reach>> reached(n);
  std::vector<float> distance(n, std::numeric_limits<float>::infinity());
  std::vector<std::uint32_t> touched;
  const std::size_t budget = kMaxReachesPerVertex * n;
  std::size_t reaches = 0;
  for (std::uint32_t node = 0; node < node_vertices.size(); ++node) {
    SpreadAlongEdges(mesh, neighbours, node_vertices[node], kNodeReachSpacings * spacing, &distance,
                     &touched, [&](std::uint32_t v, float d) {
                       if (reaches < budget) reached[v].push_back({d, node});
                       ++reaches;
                     });
    if (reaches > budget) {
      return CorruptError("deformation graph: " + std::to_string(node_vertices.size()) +
                          " nodes are too dense for their spacing " + std::to_string(spacing));
    }
  }
  const double width = 2.0 * double(spacing) * double(spacing);
  std::vector<VertexBlend> blends(n);
  for (std::uint32_t v = 0; v < n; ++v) {
    std::vector<Reach>& list = reached[v];
    if (list.empty()) {
      return CorruptError("deformation graph: no node reaches vertex " + std::to_string(v));
    }
    const std::size_t keep = std::min<std::size_t>(kMaxInfluences, list.size());
    std::partial_sort(list.begin(), list.begin() + keep, list.end());
    std::array<double, kMaxInfluences> weights{};
    double total = 0;
    for (std::size_t k = 0; k < keep; ++k) {
      weights[k] = std::exp(-double(list[k].distance) * double(list[k].distance) / width);
      total += weights[k];
    }
    // Steps of 1 / kNodeWeightSteps; the nearest node takes what rounding leaves.
    std::array<long, kMaxInfluences> steps{};
    long sum = 0;
    for (std::size_t k = 0; k < keep; ++k) {
      steps[k] = std::lround(weights[k] / total * kNodeWeightSteps);
      sum += steps[k];
    }
    steps[0] += kNodeWeightSteps - sum;
    VertexBlend& blend = blends[v];
    for (std::size_t k = 0; k < keep; ++k) {
      if (steps[k] <= 0) continue;
      blend.influences[blend.count++] = {list[k].node, float(steps[k]) / float(kNodeWeightSteps)};
    }
  }
  return blends;
}

StatusOr<MotionModel> SampleNodeMotion(const TriangleMesh& mesh,
                                       const std::vector<std::vector<std::uint32_t>>& neighbours,
                                       float spacing) {
  MotionModel model;
  model.node_vertices = SampleDeformationNodes(mesh, neighbours, spacing);
  model.segment_count = static_cast<std::uint32_t>(model.node_vertices.size());
  model.node_spacing = spacing;
  MESHVID_ASSIGN_OR_RETURN(model.blends,
                           DeriveNodeBlends(mesh, neighbours, model.node_vertices, spacing));
  return model;
}

Status CompleteNodeBlends(const TriangleMesh& mesh, MotionModel* model) {
  if (model->node_vertices.size() != model->segment_count) {
    return CorruptError("deformation graph: " + std::to_string(model->node_vertices.size()) +
                        " nodes for " + std::to_string(model->segment_count) + " segments");
  }
  MESHVID_ASSIGN_OR_RETURN(
      model->blends,
      DeriveNodeBlends(mesh, VertexNeighbours(mesh), model->node_vertices, model->node_spacing));
  return ValidateMotionModel(*model, mesh.vertex_count());
}

}  // namespace meshvid
