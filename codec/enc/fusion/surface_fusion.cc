// FuseRangeMeshes: oriented points of all views, thinned on a grid, averaged into a sparse
// truncated signed-distance volume, contoured by marching tetrahedra. A Poisson reconstruction
// closes every surface, inventing sheets far from open and thin data (a cloth, a chicken's
// wings), and is slower (bench/FUSION.md).
#include "codec/enc/fusion/surface_fusion.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "codec/common/point_tree.h"
#include "codec/enc/fusion/contour_volume.h"
#include "codec/enc/fusion/distance_volume.h"
#include "codec/enc/fusion/seen_free_space.h"

namespace meshvid {
namespace {

// Fewest points worth reconstructing from.
constexpr std::size_t kMinPoints = 100;

// Every referenced vertex of every view with its unit normal (the view's own normals if it
// has them, else area-weighted ones from its triangles, which face the sensor).
std::vector<OrientedPoint> GatherPoints(std::span<const TriangleMesh> views) {
  std::vector<OrientedPoint> points;
  std::size_t total = 0;
  for (const TriangleMesh& view : views) total += view.positions.size();
  points.reserve(total);
  std::vector<Eigen::Vector3f> computed;
  for (const TriangleMesh& view : views) {
    const bool has_normals = view.normals.size() == view.positions.size();
    if (!has_normals) ComputeVertexNormals(view.positions, view.triangles, &computed);
    const std::vector<Eigen::Vector3f>& normals = has_normals ? view.normals : computed;
    std::vector<char> used(view.positions.size(), 0);
    for (const Triangle& t : view.triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
    for (std::size_t v = 0; v < view.positions.size(); ++v) {
      const float length = normals[v].norm();
      if (!used[v] || !(length > 0.5f)) continue;
      points.push_back({view.positions[v], normals[v] / length});
    }
  }
  return points;
}

// Averages the points falling in each cell of a grid of side `cell`, keeping points whose
// normals point along different axes apart (the two sides of a thin part stay apart).
std::vector<OrientedPoint> ThinOnGrid(const std::vector<OrientedPoint>& points,
                                      const Eigen::Vector3f& origin, float cell) {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(points.size());
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f q = (points[i].position - origin) / cell;
    const Eigen::Vector3f& n = points[i].normal;
    int axis;
    n.cwiseAbs().maxCoeff(&axis);
    const std::uint64_t direction = 2 * axis + (n[axis] < 0 ? 1 : 0);
    std::uint64_t key = direction;
    for (int a = 0; a < 3; ++a) {
      key = (key << 20) | (static_cast<std::uint64_t>(std::max(0.0f, q[a])) & 0xfffff);
    }
    keys[i] = {key, i};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<OrientedPoint> thinned;
  for (std::size_t begin = 0; begin < keys.size();) {
    std::size_t end = begin;
    Eigen::Vector3f position = Eigen::Vector3f::Zero();
    Eigen::Vector3f normal = Eigen::Vector3f::Zero();
    for (; end < keys.size() && keys[end].first == keys[begin].first; ++end) {
      position += points[keys[end].second].position;
      normal += points[keys[end].second].normal;
    }
    const float length = normal.norm();
    if (length > 0) {
      thinned.push_back({position / static_cast<float>(end - begin), normal / length});
    }
    begin = end;
  }
  return thinned;
}

// Thins `points` to at most `max_points`, growing the grid cell until they fit; sets *cell to
// the cell used (0 when the points already fit).
std::vector<OrientedPoint> Thin(std::vector<OrientedPoint> points, std::size_t max_points,
                                double area, float* used_cell) {
  *used_cell = 0;
  if (points.size() <= max_points) return points;
  Eigen::AlignedBox3f box;
  for (const OrientedPoint& p : points) box.extend(p.position);
  // A surface of this area sampled on a grid of side h holds about area / h^2 points.
  float cell = static_cast<float>(std::sqrt(area / static_cast<double>(max_points)));
  cell = std::max(cell, box.diagonal().maxCoeff() / float(1 << 19));
  for (int attempt = 0; attempt < 30; ++attempt) {
    std::vector<OrientedPoint> thinned = ThinOnGrid(points, box.min(), cell);
    *used_cell = cell;
    if (thinned.size() <= max_points) return thinned;
    cell *= std::max(1.02f, 1.02f * std::sqrt(static_cast<float>(thinned.size()) /
                                              static_cast<float>(max_points)));
  }
  *used_cell = cell * 4;
  return ThinOnGrid(points, box.min(), cell * 4);
}

// Keeps one side of sheets thinner than a voxel that views see from both sides (a cloth on
// a ring of sensors): there the two sides' signed distances cancel and no surface could come
// out. A point is two-sided when a point of opposite normal lies less than a voxel behind it;
// of those, the ones facing away from the two-sided points' main normal axis are dropped, so
// such a sheet fuses as one open surface (a fold turning past that axis keeps both sides and
// may come out broken). Returns how many points were dropped.
std::size_t KeepOneSideOfTwoSidedSheets(std::vector<OrientedPoint>* points, float voxel) {
  std::vector<Eigen::Vector3f> positions(points->size());
  for (std::size_t i = 0; i < points->size(); ++i) positions[i] = (*points)[i].position;
  const PointCloud cloud{positions};
  PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
  tree.buildIndex();
  constexpr std::size_t kNeighbours = 8;
  std::vector<char> two_sided(points->size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points->size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
    std::uint32_t nearest[kNeighbours];
    float squared[kNeighbours];
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const OrientedPoint& p = (*points)[i];
      const std::size_t found = tree.knnSearch(p.position.data(), kNeighbours, nearest, squared);
      for (std::size_t k = 0; k < found; ++k) {
        const OrientedPoint& q = (*points)[nearest[k]];
        const float behind = p.normal.dot(p.position - q.position);
        if (p.normal.dot(q.normal) < -0.5f && behind > -0.5f * voxel && behind < voxel) {
          two_sided[i] = 1;
          break;
        }
      }
    }
  });
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  std::size_t count = 0;
  for (std::size_t i = 0; i < points->size(); ++i) {
    if (!two_sided[i]) continue;
    const Eigen::Vector3d n = (*points)[i].normal.cast<double>();
    scatter += n * n.transpose();
    ++count;
  }
  if (count == 0) return 0;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  const Eigen::Vector3f axis = solver.eigenvectors().col(2).cast<float>();  // largest
  std::size_t kept = 0;
  for (std::size_t i = 0; i < points->size(); ++i) {
    if (two_sided[i] && (*points)[i].normal.dot(axis) < 0) continue;
    (*points)[kept++] = (*points)[i];
  }
  const std::size_t dropped = points->size() - kept;
  points->resize(kept);
  return dropped;
}

// Keeps the sets of triangles connected through shared vertices that hold at least
// `min_share` of the triangles, and the largest one in any case.
void KeepMainPieces(TriangleMesh* mesh, double min_share) {
  std::vector<std::uint32_t> parent(mesh->positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&parent](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const Triangle& t : mesh->triangles) {
    for (int c = 1; c < 3; ++c) {
      const std::uint32_t a = find(t[0]), b = find(t[c]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<std::size_t> size(parent.size(), 0);
  for (const Triangle& t : mesh->triangles) ++size[find(t[0])];
  const std::size_t largest = *std::max_element(size.begin(), size.end());
  const double least = std::min(static_cast<double>(largest),
                                min_share * static_cast<double>(mesh->triangles.size()));
  std::erase_if(mesh->triangles, [&](const Triangle& t) {
    return static_cast<double>(size[find(t[0])]) < least;
  });
  RemoveUnreferencedVertices(mesh);
}

// Removes the triangles of `mesh` whose centre is farther than `limit` (when > 0) from every
// point of `data`, or lies where a camera saw through it (`free_space`, by more than
// `free_space_tolerance`), peeling from the boundary inwards: such a triangle goes only once
// it touches the boundary (through triangles removed before it), so sparse or missing data
// inside the surface makes no hole.
void TrimBeyondData(std::span<const Eigen::Vector3f> data, float limit,
                    const SeenFreeSpace& free_space, float free_space_tolerance,
                    TriangleMesh* mesh) {
  const bool measure = limit > 0 && !data.empty();
  const PointCloud cloud{data};
  std::optional<PointTree> tree;
  if (measure) {
    tree.emplace(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
  }
  const std::size_t count = mesh->triangles.size();
  std::vector<char> far(count);
  const float limit_squared = limit * limit;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const auto& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const Triangle& t = mesh->triangles[i];
      const Eigen::Vector3f centre =
          (mesh->positions[t[0]] + mesh->positions[t[1]] + mesh->positions[t[2]]) / 3;
      if (measure) {
        std::uint32_t nearest = 0;
        float squared = 0;
        tree->knnSearch(centre.data(), 1, &nearest, &squared);
        far[i] = squared > limit_squared;
      }
      if (!far[i] && free_space.view_count() > 0) {
        const Eigen::Vector3f normal = (mesh->positions[t[1]] - mesh->positions[t[0]])
                                           .cross(mesh->positions[t[2]] - mesh->positions[t[0]])
                                           .normalized();
        far[i] = free_space.Contains(centre, normal, free_space_tolerance);
      }
    }
  });
  // Undirected edges with their triangle, sorted so that the uses of one edge are adjacent.
  struct EdgeUse {
    std::uint32_t a, b, triangle;
    bool operator<(const EdgeUse& o) const { return a != o.a ? a < o.a : b < o.b; }
  };
  std::vector<EdgeUse> edges;
  edges.reserve(3 * count);
  for (std::size_t i = 0; i < count; ++i) {
    const Triangle& t = mesh->triangles[i];
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = t[c], b = t[(c + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), static_cast<std::uint32_t>(i)});
    }
  }
  std::sort(edges.begin(), edges.end());
  // Per triangle, the triangles across its edges; far triangles on the boundary (an edge
  // used once) start the peeling.
  std::vector<std::vector<std::uint32_t>> across(count);
  std::vector<char> removed(count, 0);
  std::vector<std::uint32_t> queue;
  for (std::size_t begin = 0, end = 0; begin < edges.size(); begin = end) {
    end = begin + 1;
    while (end < edges.size() && edges[end].a == edges[begin].a &&
           edges[end].b == edges[begin].b) {
      ++end;
    }
    const std::uint32_t t = edges[begin].triangle;
    if (end - begin == 1 && far[t] && !removed[t]) removed[t] = 1, queue.push_back(t);
    for (std::size_t i = begin; i < end; ++i) {
      for (std::size_t j = begin; j < end; ++j) {
        if (i != j) across[edges[i].triangle].push_back(edges[j].triangle);
      }
    }
  }
  while (!queue.empty()) {
    const std::uint32_t t = queue.back();
    queue.pop_back();
    for (std::uint32_t u : across[t]) {
      if (far[u] && !removed[u]) removed[u] = 1, queue.push_back(u);
    }
  }
  std::size_t next = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (!removed[i]) mesh->triangles[next++] = mesh->triangles[i];
  }
  mesh->triangles.resize(next);
  RemoveUnreferencedVertices(mesh);
}

/// The fusion's voxel: the options' spacing, or the views' `sample_spacing` or the thinning's
/// cell scaled; never so fine that the volume would hold more than max_voxels or outrun its
/// index range.
double VoxelSize(const SurfaceFusionOptions& options, double area, double sample_spacing,
                 float thinning_cell, const Eigen::AlignedBox3f& box) {
  double voxel = options.spacing;
  if (voxel == 0) {
    voxel = options.voxel_scale * std::max<double>(sample_spacing, thinning_cell);
  }
  // Each point writes a ball of the band's radius; the band covers about area / voxel^2
  // columns of 2 * truncation + 1 voxels (overlapping views write the same voxels, so this
  // over-estimates); blocks of 8^3 voxels round it up.
  const double band = 2 * options.truncation_voxels + 1;
  const double min_voxel = box.diagonal().maxCoeff() / double(1 << 18);  // index range
  return std::max(
      {voxel, min_voxel, std::sqrt(area * band * 4 / static_cast<double>(options.max_voxels))});
}

/// kInvalidArgument unless every view is a valid mesh and every option is in range.
Status CheckFusionInput(std::span<const TriangleMesh> views, const SurfaceFusionOptions& options) {
  if (views.empty()) return InvalidArgumentError("surface fusion needs at least one view");
  for (std::size_t v = 0; v < views.size(); ++v) {
    MESHVID_RETURN_IF_ERROR(ValidateMesh(views[v], "view " + std::to_string(v) + " to fuse"));
  }
  auto finite_positive = [](double x) { return std::isfinite(x) && x > 0; };
  if (!(options.spacing >= 0) || !std::isfinite(options.spacing)) {
    return InvalidArgumentError("surface fusion spacing must be finite and >= 0");
  }
  if (!(options.max_extension_spacings >= 0) || !std::isfinite(options.max_extension_spacings)) {
    return InvalidArgumentError("surface fusion max_extension_spacings must be finite and >= 0");
  }
  if (!(options.free_space_tolerance_spacings >= 0) ||
      !std::isfinite(options.free_space_tolerance_spacings) ||
      options.free_space_margin_pixels < 0 || options.free_space_margin_pixels > 16) {
    return InvalidArgumentError("surface fusion free_space_tolerance_spacings must be finite "
                                "and >= 0, free_space_margin_pixels in [0, 16]");
  }
  if (!finite_positive(options.voxel_scale) || !finite_positive(options.truncation_voxels) ||
      !finite_positive(options.support_voxels) || options.truncation_voxels > 7) {
    return InvalidArgumentError("surface fusion voxel_scale and support_voxels must be finite "
                                "and > 0, truncation_voxels in (0, 7]");
  }
  if (!(options.min_piece_share >= 0 && options.min_piece_share <= 1)) {
    return InvalidArgumentError("surface fusion min_piece_share must be in [0, 1]");
  }
  if (options.max_points < kMinPoints) {
    return InvalidArgumentError("surface fusion max_points must be at least " +
                                std::to_string(kMinPoints));
  }
  if (options.max_voxels < 1000) {
    return InvalidArgumentError("surface fusion max_voxels must be at least 1000");
  }
  return Status::Ok();
}

}  // namespace

StatusOr<TriangleMesh> FuseRangeMeshes(std::span<const TriangleMesh> views,
                                       const SurfaceFusionOptions& options,
                                       const ProgressCallback& progress) {
  MESHVID_RETURN_IF_ERROR(CheckFusionInput(views, options));
  constexpr long kStages = 3;
  if (!ReportProgress(progress, "fusion: points", 0, kStages)) {
    return CancelledError("surface fusion cancelled");
  }
  double area = 0;
  for (const TriangleMesh& view : views) area += SurfaceArea(view);
  if (!(area > 0) || !std::isfinite(area)) {
    return InvalidArgumentError("surface fusion: the views have no area (degenerate triangles)");
  }
  std::vector<OrientedPoint> gathered = GatherPoints(views);
  const std::size_t gathered_count = gathered.size();
  std::vector<Eigen::Vector3f> unthinned;  // what the trim measures against (max_extension)
  if (options.max_extension_spacings > 0) {
    unthinned.reserve(gathered_count);
    for (const OrientedPoint& p : gathered) unthinned.push_back(p.position);
  }
  float thinning_cell = 0;
  std::vector<OrientedPoint> points =
      Thin(std::move(gathered), options.max_points, area, &thinning_cell);
  if (points.size() < kMinPoints) {
    return InvalidArgumentError("surface fusion: the views hold " +
                                std::to_string(points.size()) + " usable points, fewer than " +
                                std::to_string(kMinPoints));
  }
  Eigen::AlignedBox3f box;
  for (const OrientedPoint& p : points) box.extend(p.position);
  if (!(box.diagonal().norm() > 0)) {
    return InvalidArgumentError("surface fusion: the input points are all at one place");
  }
  // A view sampled every s holds about area / s^2 points.
  const double sample_spacing = std::sqrt(area / static_cast<double>(gathered_count));
  const double voxel = VoxelSize(options, area, sample_spacing, thinning_cell, box);
  if (!(voxel > 0) || !std::isfinite(voxel)) {
    return InvalidArgumentError("surface fusion: no voxel size fits the views");
  }
  if (!ReportProgress(progress, "fusion: volume", 1, kStages)) {
    return CancelledError("surface fusion cancelled");
  }
  DistanceVolumeSettings settings;
  settings.voxel_size = static_cast<float>(voxel);
  settings.truncation_voxels = static_cast<float>(options.truncation_voxels);
  settings.support_voxels = static_cast<float>(options.support_voxels);
  // The grid is anchored off the data's centre by odd fractions of a voxel, so that flat data
  // on round coordinates does not sit exactly on grid corners (which gives coincident
  // vertices and zero-area triangles).
  const Eigen::Vector3f offset = Eigen::Vector3f(0.31f, 0.47f, 0.13f) * settings.voxel_size;
  DistanceVolume volume(box.center() + offset, settings);
  KeepOneSideOfTwoSidedSheets(&points, settings.voxel_size);
  volume.Integrate(points);
  if (!ReportProgress(progress, "fusion: contour", 2, kStages)) {
    return CancelledError("surface fusion cancelled");
  }
  TriangleMesh result = ContourDistanceVolume(volume);
  double max_extension = options.max_extension_spacings * sample_spacing;
  if (!(max_extension < options.support_voxels * voxel)) max_extension = 0;  // no trim needed
  const SeenFreeSpace free_space(views, options.view_cameras, options.free_space_margin_pixels);
  if ((max_extension > 0 || free_space.view_count() > 0) && !result.triangles.empty()) {
    // Within the volume's band the fusion itself averages the views (a small misregistration
    // between them included), so the tolerance is at least the band.
    const double tolerance = std::max(options.free_space_tolerance_spacings * sample_spacing,
                                      options.truncation_voxels * voxel);
    TrimBeyondData(unthinned, static_cast<float>(max_extension), free_space,
                   static_cast<float>(tolerance), &result);
  }
  if (!result.triangles.empty()) KeepMainPieces(&result, options.min_piece_share);
  if (result.triangles.empty()) {
    return InvalidArgumentError(
        "surface fusion: the views give no surface (too sparse or degenerate for a voxel "
        "size of " + std::to_string(voxel) + ")");
  }
  result.normals = ComputeVertexNormals(result);
  ReportProgress(progress, "fusion: done", kStages, kStages);
  return result;
}

}  // namespace meshvid
