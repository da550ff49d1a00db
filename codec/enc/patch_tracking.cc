#include "codec/enc/patch_tracking.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>

#include <Eigen/Geometry>

#include "codec/enc/graph_tracking.h"

namespace meshvid {
namespace {

constexpr float kFar = std::numeric_limits<float>::infinity();

/// Dijkstra along the mesh's edges from `source`, restricted to vertices with
/// region[v] == region_id, lowering `distance` (and setting `owner` to `owner_id`) where the
/// new path is shorter.
void RelaxFrom(const TriangleMesh& base, const std::vector<std::vector<std::uint32_t>>& neighbours,
               const std::vector<std::int32_t>& region, std::int32_t region_id,
               std::uint32_t source, std::int32_t owner_id, std::vector<float>* distance,
               std::vector<std::int32_t>* owner) {
  using Entry = std::pair<float, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  (*distance)[source] = 0;
  (*owner)[source] = owner_id;
  queue.push({0.0f, source});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > (*distance)[v]) continue;
    for (std::uint32_t w : neighbours[v]) {
      if (region[w] != region_id) continue;
      const float next = d + (base.positions[v] - base.positions[w]).norm();
      if (next < (*distance)[w]) {
        (*distance)[w] = next;
        (*owner)[w] = owner_id;
        queue.push({next, w});
      }
    }
  }
}

}  // namespace

int PartitionUnregistered(const BaseTopology& topology, int segment_count,
                          int min_patch_vertices, const PatchTrackingOptions& options,
                          std::vector<std::int32_t>* labels) {
  const TriangleMesh& base = topology.mesh;
  const std::size_t n = base.vertex_count();
  const int budget = options.max_segments - segment_count;
  if (budget <= 0 || options.patch_vertices < 1) return segment_count;
  const auto& neighbours = topology.neighbours;
  // Connected regions of unregistered vertices.
  std::vector<std::int32_t> region(n, -1);
  std::vector<std::vector<std::uint32_t>> regions;
  for (std::uint32_t v = 0; v < n; ++v) {
    if ((*labels)[v] >= 0 || region[v] >= 0) continue;
    const auto id = static_cast<std::int32_t>(regions.size());
    regions.emplace_back();
    std::vector<std::uint32_t> stack{v};
    region[v] = id;
    while (!stack.empty()) {
      const std::uint32_t u = stack.back();
      stack.pop_back();
      regions[id].push_back(u);
      for (std::uint32_t w : neighbours[u]) {
        if ((*labels)[w] < 0 && region[w] < 0) {
          region[w] = id;
          stack.push_back(w);
        }
      }
    }
  }
  // Patches per region: in proportion to its size, largest regions first within the budget.
  std::vector<std::size_t> order(regions.size());
  for (std::size_t r = 0; r < order.size(); ++r) order[r] = r;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return regions[a].size() > regions[b].size(); });
  std::size_t wanted = 0;
  for (const auto& r : regions) {
    if (r.size() < std::size_t(std::max(3, min_patch_vertices))) continue;
    wanted += std::max<std::size_t>(1, r.size() / std::size_t(options.patch_vertices));
  }
  const double share = wanted > std::size_t(budget) ? double(budget) / double(wanted) : 1.0;
  int next = segment_count;
  std::vector<float> distance(n, kFar);
  std::vector<std::int32_t> owner(n, -1);
  for (std::size_t r : order) {
    const auto& vertices = regions[r];
    if (vertices.size() < std::size_t(std::max(3, min_patch_vertices))) break;
    const int left = options.max_segments - next;
    if (left <= 0) break;
    int count = std::max(1, static_cast<int>(share * double(std::max<std::size_t>(
                                                         1, vertices.size() /
                                                                std::size_t(options.patch_vertices)))));
    count = std::min(count, left);
    // Farthest-point seeds along the edges, then every vertex to its nearest seed.
    RelaxFrom(base, neighbours, region, std::int32_t(r), vertices.front(), -1, &distance, &owner);
    std::uint32_t seed = vertices.front();
    for (std::uint32_t v : vertices) {
      if (distance[v] > distance[seed] || std::isinf(distance[seed])) seed = v;
    }
    for (std::uint32_t v : vertices) distance[v] = kFar;
    for (int k = 0; k < count; ++k) {
      RelaxFrom(base, neighbours, region, std::int32_t(r), seed, next + k, &distance, &owner);
      for (std::uint32_t v : vertices) {
        if (distance[v] > distance[seed]) seed = v;
      }
    }
    // Compact: patches that ended up tiny stay unregistered (they are interpolated).
    std::vector<std::size_t> sizes(count, 0);
    for (std::uint32_t v : vertices) ++sizes[owner[v] - next];
    std::vector<std::int32_t> renumber(count, -1);
    int kept = 0;
    for (int k = 0; k < count; ++k) {
      if (sizes[k] >= 3) renumber[k] = next + kept++;
    }
    for (std::uint32_t v : vertices) (*labels)[v] = renumber[owner[v] - next];
    next += kept;
  }
  return next;
}

Status TrackPatches(const BaseTopology& topology, const std::vector<std::int32_t>& labels,
                    int fixed_count, int total_count, FrameTargets targets,
                    const SegmentationOptions& seg, const PatchTrackingOptions& options,
                    std::vector<std::vector<RigidTransform>>* transforms,
                    const ProgressCallback& progress) {
  if (transforms->size() != targets.size()) {
    return InvalidArgumentError("patch tracking: " + std::to_string(transforms->size()) +
                                " frames of transforms for " + std::to_string(targets.size()) +
                                " targets");
  }
  for (auto& frame : *transforms) frame.resize(total_count);
  if (total_count <= fixed_count || targets.empty()) return Status::Ok();
  const PieceGraph graph = BuildPieceGraph(topology, labels, fixed_count, total_count);
  JointStepSettings settings;
  settings.shot = seg.shot;
  settings.stiffness = options.stiffness;
  const int frames = static_cast<int>(targets.size());
  for (int k = 1; k < frames; ++k) {
    if (!ReportProgress(progress, "patch tracking", k, frames)) {
      return CancelledError("patch tracking cancelled");
    }
    std::vector<RigidTransform>& frame = (*transforms)[k];
    for (int s = fixed_count; s < total_count; ++s) {
      frame[s] = k < 2 ? (*transforms)[k - 1][s]
                       : PredictConstantVelocity((*transforms)[k - 2][s], (*transforms)[k - 1][s]);
    }
    if (targets[k] == nullptr) continue;
    SolveJointly(topology, graph, *targets[k], seg, settings, /*fine_only=*/false, &frame);
  }
  return Status::Ok();
}

int MergePatchesIntoSegments(const BaseTopology& topology, int fixed_count, int total_count,
                             const SegmentationOptions& seg, std::vector<std::int32_t>* labels,
                             std::vector<std::vector<RigidTransform>>* transforms) {
  const TriangleMesh& base = topology.mesh;
  const int patches = total_count - fixed_count;
  if (patches <= 0 || fixed_count <= 0) return total_count;
  std::vector<std::vector<std::uint32_t>> members(patches);
  for (std::uint32_t v = 0; v < labels->size(); ++v) {
    const std::int32_t l = (*labels)[v];
    if (l >= fixed_count && l < total_count) members[l - fixed_count].push_back(v);
  }
  const auto& neighbours = topology.neighbours;
  // Passes until nothing joins: a patch joining a segment makes the segment adjacent to
  // the patches beyond it.
  std::vector<std::int32_t> target(patches, -1);
  for (bool joined = true; joined;) {
    joined = false;
    for (int p = 0; p < patches; ++p) {
      if (target[p] >= 0) continue;
      std::vector<std::int32_t> adjacent;
      for (std::uint32_t v : members[p]) {
        for (std::uint32_t w : neighbours[v]) {
          const std::int32_t l = (*labels)[w];
          if (l >= 0 && l < fixed_count &&
              std::find(adjacent.begin(), adjacent.end(), l) == adjacent.end()) {
            adjacent.push_back(l);
          }
        }
      }
      double best = std::numeric_limits<double>::infinity();
      for (std::int32_t s : adjacent) {
        // Frames in which the two tracks disagree on the patch, and the summed RMS.
        int disagree = 0;
        double total = 0;
        for (const auto& frame : *transforms) {
          double squared = 0;
          for (std::uint32_t v : members[p]) {
            squared += (frame[fixed_count + p].Apply(base.positions[v]) -
                        frame[s].Apply(base.positions[v]))
                           .squaredNorm();
          }
          const double rms = std::sqrt(squared / double(members[p].size()));
          if (rms > seg.tolerance) ++disagree;
          total += rms;
        }
        if (disagree <= seg.occlusion_frames && total < best) best = total, target[p] = s;
      }
      if (target[p] >= 0) {
        for (std::uint32_t v : members[p]) (*labels)[v] = target[p];
        joined = true;
      }
    }
  }
  std::vector<std::int32_t> renumber(patches);
  int next = fixed_count;
  for (int p = 0; p < patches; ++p) renumber[p] = target[p] >= 0 ? target[p] : next++;
  for (auto& l : *labels) {
    if (l >= fixed_count && l < total_count) l = renumber[l - fixed_count];
  }
  for (auto& frame : *transforms) {
    std::vector<RigidTransform> kept(frame.begin(), frame.begin() + fixed_count);
    for (int p = 0; p < patches; ++p) {
      if (target[p] < 0) kept.push_back(frame[fixed_count + p]);
    }
    frame = std::move(kept);
  }
  return next;
}

}  // namespace meshvid
