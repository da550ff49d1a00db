#include "codec/enc/key_groups/detail.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meshvid {

namespace {

/// |cos| of the angle at which a camera (or, without one, the shot) sees `hit`.
float SeenCos(const ShotHit& hit, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
              const ViewCalibration* camera) {
  const Eigen::Vector3f point = origin + hit.distance * direction;
  const Eigen::Vector3f ray =
      camera != nullptr
          ? Eigen::Vector3f(point - camera->world_from_camera.translation().cast<float>())
          : direction;
  const float length = ray.norm();
  return length > 0 ? std::abs(hit.normal.dot(ray)) / length : 0.0f;
}

}  // namespace

StatusOr<std::size_t> MeasureDisplacements(const RegularSubdivision& subdivision,
                                           std::span<const Eigen::Vector3f> positions,
                                           std::span<const TriangleMesh> views,
                                           const DetailOptions& options,
                                           std::vector<float>* displacements,
                                           std::span<const ViewCalibration> cameras,
                                           ColourObservations* colours) {
  if (positions.size() != subdivision.base_vertex_count()) {
    return InvalidArgumentError("posed base has " + std::to_string(positions.size()) +
                                " vertices, the lattice " +
                                std::to_string(subdivision.base_vertex_count()));
  }
  std::vector<Eigen::Vector3f> normals, origins, directions;
  ComputeVertexNormals(positions, subdivision.base_triangles(), &normals);
  EvaluateSampleFrames(subdivision, subdivision.levels(), positions, normals, &origins,
                       &directions);
  const std::size_t samples = origins.size();
  std::vector<std::vector<float>> per_view(views.size());
  if (colours != nullptr) colours->Reset(views.size(), samples);
  std::vector<ShotHit> hits_of_view;
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (views[v].empty()) {
      per_view[v].assign(samples, kNoHit);
      continue;
    }
    MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<ShootingTarget> target,
                             ShootingTarget::Create(views[v]));
    if (colours == nullptr || views[v].colours.empty()) {
      target->ShootAll(origins, directions, options.shot, &per_view[v]);
      continue;
    }
    target->ShootAllHits(origins, directions, options.shot, &hits_of_view);
    const ViewCalibration* camera =
        v < cameras.size() && cameras[v].has_extrinsics ? &cameras[v] : nullptr;
    per_view[v].resize(samples);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples, 4096), [&](const auto& range) {
      for (std::size_t i = range.begin(); i < range.end(); ++i) {
        const ShotHit& hit = hits_of_view[i];
        per_view[v][i] = hit.distance;
        if (!hit.hit()) continue;
        colours->colour[v][i] =
            BlendColours(views[v].colours, views[v].triangles[hit.triangle], hit.u, hit.v);
        colours->weight[v][i] = ViewingWeight(SeenCos(hit, origins[i], directions[i], camera));
      }
    });
  }
  displacements->assign(samples, kNoHit);
  std::size_t hits = 0;
  std::vector<float> found;
  for (std::size_t i = 0; i < samples; ++i) {
    found.clear();
    for (const auto& view : per_view) {
      if (!std::isnan(view[i])) found.push_back(view[i]);
    }
    if (found.empty()) continue;
    // Eq. 4 with outlier rejection: average the hits near the views' median.
    std::nth_element(found.begin(), found.begin() + found.size() / 2, found.end());
    float median = found[found.size() / 2];
    if (found.size() % 2 == 0) {
      median = 0.5f * (median + *std::max_element(found.begin(), found.begin() + found.size() / 2));
    }
    double sum = 0;
    int count = 0;
    for (float d : found) {
      if (std::abs(d - median) <= options.outlier_distance) sum += d, ++count;
    }
    (*displacements)[i] = count > 0 ? float(sum / count) : median;
    ++hits;
    if (colours != nullptr) {
      // Colour only from the hits the displacement kept (if it kept none, the hits nearest
      // the median it took instead).
      float tolerance = options.outlier_distance;
      if (count == 0) {
        tolerance = std::numeric_limits<float>::infinity();
        for (float d : found) tolerance = std::min(tolerance, std::abs(d - median));
      }
      for (std::size_t v = 0; v < per_view.size(); ++v) {
        if (!(std::abs(per_view[v][i] - median) <= tolerance)) colours->weight[v][i] = 0;
      }
    }
  }
  return hits;
}

SampleGraph SampleGraph::Build(const RegularSubdivision& subdivision) {
  const std::size_t samples = subdivision.samples().size();
  std::vector<std::vector<std::uint32_t>> lists(samples);
  for (const Triangle& t : subdivision.Triangles(subdivision.levels())) {
    for (int c = 0; c < 3; ++c) {
      lists[t[c]].push_back(t[(c + 1) % 3]);
      lists[t[c]].push_back(t[(c + 2) % 3]);
    }
  }
  SampleGraph graph;
  graph.offsets.reserve(samples + 1);
  graph.offsets.push_back(0);
  for (auto& list : lists) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    graph.neighbours.insert(graph.neighbours.end(), list.begin(), list.end());
    graph.offsets.push_back(static_cast<std::uint32_t>(graph.neighbours.size()));
  }
  return graph;
}

namespace {

/// What no measurement reaches in `frame`: spread from filled neighbours, ring by ring (a
/// multi-source breadth-first order, so each sample averages the neighbours of earlier
/// rings); where no value reaches (a part of the lattice apart from every measurement), the
/// fill `unreached` asks for. Without `unreached.spread_everywhere`, the first ring is seeded
/// from the samples queued so far, in index order, so a sample can join it with no valued
/// neighbour and take 0.
void SpreadIntoUnreached(const SampleGraph& graph, const UnreachedFill& unreached,
                         std::vector<float>* frame_values) {
  std::vector<float>& frame = *frame_values;
  const std::size_t samples = frame.size();
  float apart = unreached.no_values;
  if (unreached.frame_mean) {
    double sum = 0;
    std::size_t count = 0;
    for (float value : frame) {
      if (!std::isnan(value)) sum += value, ++count;
    }
    if (count > 0) apart = static_cast<float>(sum / count);
  }
  std::vector<std::uint32_t> ring, next_ring;
  std::vector<float> values;
  std::vector<char> queued(samples);
  for (std::uint32_t i = 0; i < samples; ++i) {
    queued[i] = !std::isnan(frame[i]);
  }
  for (std::uint32_t i = 0; i < samples; ++i) {
    if (unreached.spread_everywhere ? std::isnan(frame[i]) : !queued[i]) continue;
    for (std::uint32_t k = graph.offsets[i]; k < graph.offsets[i + 1]; ++k) {
      const std::uint32_t n = graph.neighbours[k];
      if (!queued[n]) queued[n] = 1, ring.push_back(n);
    }
  }
  while (!ring.empty()) {
    values.resize(ring.size());
    for (std::size_t r = 0; r < ring.size(); ++r) {
      double sum = 0;
      int terms = 0;
      const std::uint32_t i = ring[r];
      for (std::uint32_t k = graph.offsets[i]; k < graph.offsets[i + 1]; ++k) {
        const float n = frame[graph.neighbours[k]];
        if (!std::isnan(n)) sum += n, ++terms;
      }
      values[r] = terms > 0 ? float(sum / terms) : 0.0f;
    }
    next_ring.clear();
    for (std::size_t r = 0; r < ring.size(); ++r) {
      const std::uint32_t i = ring[r];
      frame[i] = values[r];
      for (std::uint32_t k = graph.offsets[i]; k < graph.offsets[i + 1]; ++k) {
        const std::uint32_t n = graph.neighbours[k];
        if (!queued[n]) queued[n] = 1, next_ring.push_back(n);
      }
    }
    ring.swap(next_ring);
  }
  for (std::size_t i = 0; i < samples; ++i) {
    if (std::isnan(frame[i])) frame[i] = apart;
  }
}

}  // namespace

std::size_t FillDisplacementGroup(const SampleGraph& graph, std::vector<float>* last_measured,
                                  std::vector<std::vector<float>>* frames,
                                  const UnreachedFill& unreached) {
  const std::size_t count = frames->size();
  if (count == 0) return 0;
  const std::size_t samples = (*frames)[0].size();
  last_measured->resize(samples, kNoHit);
  std::size_t filled = 0;
  std::vector<std::vector<float>> result = *frames;
  // Temporal and one-ring spatial candidates, from measurements only.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples, 4096), [&](const auto& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      float before = (*last_measured)[i];
      for (std::size_t f = 0; f < count; ++f) {
        const float value = (*frames)[f][i];
        if (!std::isnan(value)) {
          before = value;
          continue;
        }
        float after = kNoHit;
        for (std::size_t g = f + 1; g < count; ++g) {
          if (!std::isnan((*frames)[g][i])) {
            after = (*frames)[g][i];
            break;
          }
        }
        double sum = 0;
        int terms = 0;
        if (!std::isnan(before)) sum += before, ++terms;
        if (!std::isnan(after)) sum += after, ++terms;
        double spatial = 0;
        int neighbours = 0;
        for (std::uint32_t k = graph.offsets[i]; k < graph.offsets[i + 1]; ++k) {
          const float n = (*frames)[f][graph.neighbours[k]];
          if (!std::isnan(n)) spatial += n, ++neighbours;
        }
        if (neighbours > 0) sum += spatial / neighbours, ++terms;
        if (terms > 0) result[f][i] = float(sum / terms);
      }
    }
  });
  for (std::size_t f = 0; f < count; ++f) {
    for (std::size_t i = 0; i < samples; ++i) {
      if (!std::isnan((*frames)[f][i])) (*last_measured)[i] = (*frames)[f][i];
    }
  }
  for (std::size_t f = 0; f < count; ++f) {
    SpreadIntoUnreached(graph, unreached, &result[f]);
    for (std::size_t i = 0; i < samples; ++i) {
      if (std::isnan((*frames)[f][i])) ++filled;
    }
  }
  frames->swap(result);
  return filled;
}

}  // namespace meshvid
