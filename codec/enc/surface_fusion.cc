// FuseRangeMeshes: oriented points of all views, thinned on a grid, then CGAL's Poisson
// surface reconstruction (Kazhdan et al. 2006 on a refined Delaunay triangulation) contoured
// by CGAL's surface mesher with the manifold tag, which yields a closed surface. Poisson
// needs oriented normals, which range images give for free (they face their sensor, i.e.
// out of the object). Chosen over CGAL's advancing-front and scale-space reconstructions,
// which interpolate the points and leave holes open: Poisson closes holes and averages noise.
// Measured (one core): 60k points, 2.0-2.4 s (Stanford bunny, 10 scans; a simulated samba
// frame, 3 views), of which 1.4 s is the Poisson solve. CGAL stays inside this file: its
// headers are heavy to compile.
#include "codec/enc/surface_fusion.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED 1  // Poisson's default sparse solver is Eigen's conjugate gradient
#endif
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/facets_in_complex_2_to_triangle_mesh.h>
#include <CGAL/Implicit_surface_3.h>
#include <CGAL/Poisson_reconstruction_function.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_default_triangulation_3.h>
#include <CGAL/compute_average_spacing.h>
#include <CGAL/make_surface_mesh.h>
#include <CGAL/property_map.h>

namespace meshvid {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using PointWithNormal = std::pair<Point, Vector>;

// Fewest points worth reconstructing from.
constexpr std::size_t kMinPoints = 100;

struct OrientedPoint {
  Eigen::Vector3f position;
  Eigen::Vector3f normal;
};

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

// Thins `points` to at most `max_points`, growing the grid cell until they fit.
std::vector<OrientedPoint> Thin(std::vector<OrientedPoint> points, std::size_t max_points,
                                double area) {
  if (points.size() <= max_points) return points;
  Eigen::AlignedBox3f box;
  for (const OrientedPoint& p : points) box.extend(p.position);
  // A surface of this area sampled on a grid of side h holds about area / h^2 points.
  float cell = static_cast<float>(std::sqrt(area / static_cast<double>(max_points)));
  cell = std::max(cell, box.diagonal().maxCoeff() / float(1 << 19));
  for (int attempt = 0; attempt < 30; ++attempt) {
    std::vector<OrientedPoint> thinned = ThinOnGrid(points, box.min(), cell);
    if (thinned.size() <= max_points) return thinned;
    cell *= std::max(1.02f, 1.02f * std::sqrt(static_cast<float>(thinned.size()) /
                                              static_cast<float>(max_points)));
  }
  return ThinOnGrid(points, box.min(), cell * 4);
}

// Keeps the largest set of triangles connected through shared vertices.
void KeepLargestComponent(TriangleMesh* mesh) {
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
  const std::uint32_t largest =
      static_cast<std::uint32_t>(std::max_element(size.begin(), size.end()) - size.begin());
  std::erase_if(mesh->triangles, [&](const Triangle& t) { return find(t[0]) != largest; });
  RemoveUnreferencedVertices(mesh);
}

// Puts vertices in lexicographic order of position and triangles in order of their corner
// indices (each rotated to start at its smallest, keeping its orientation). CGAL's mesher
// visits elements in an order that depends on memory addresses, so within one process the
// same input can come out permuted; this makes the output a function of the geometry only.
void Canonicalize(TriangleMesh* mesh) {
  const std::vector<Eigen::Vector3f>& p = mesh->positions;
  std::vector<std::uint32_t> order(p.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&p](std::uint32_t a, std::uint32_t b) {
    return std::lexicographical_compare(p[a].data(), p[a].data() + 3, p[b].data(),
                                        p[b].data() + 3);
  });
  std::vector<std::uint32_t> rank(p.size());
  std::vector<Eigen::Vector3f> positions(p.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) {
    rank[order[i]] = i;
    positions[i] = p[order[i]];
  }
  mesh->positions = std::move(positions);
  for (Triangle& t : mesh->triangles) {
    t = Triangle(rank[t[0]], rank[t[1]], rank[t[2]]);
    while (t[0] > t[1] || t[0] > t[2]) t = Triangle(t[1], t[2], t[0]);
  }
  std::sort(mesh->triangles.begin(), mesh->triangles.end(), [](const Triangle& a, const Triangle& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
}

// Six times the signed volume enclosed by the (closed) mesh.
double SignedVolume6(const TriangleMesh& mesh) {
  double volume = 0;
  for (const Triangle& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.positions[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.positions[t[2]].cast<double>();
    volume += a.dot(b.cross(c));
  }
  return volume;
}

/// Thrown by BoundedCriteria when the mesher's triangulation outgrows its bound.
struct MesherTooLarge {};

/// CGAL's default meshing criteria, with a bound on the triangulation's size: checked on
/// every facet the mesher considers, so a run-away refinement ends instead of exhausting
/// memory.
template <class Tr>
class BoundedCriteria : public CGAL::Surface_mesh_default_criteria_3<Tr> {
 public:
  using Base = CGAL::Surface_mesh_default_criteria_3<Tr>;
  BoundedCriteria(double angle, double radius, double distance, const Tr* triangulation,
                  std::size_t max_vertices)
      : Base(angle, radius, distance),
        triangulation_(triangulation),
        max_vertices_(max_vertices) {}
  bool is_bad(const typename Base::Facet& f, typename Base::Quality& q) const {
    if (triangulation_->number_of_vertices() > max_vertices_) throw MesherTooLarge{};
    return Base::is_bad(f, q);
  }

 private:
  const Tr* triangulation_;
  std::size_t max_vertices_;
};

}  // namespace

StatusOr<TriangleMesh> FuseRangeMeshes(std::span<const TriangleMesh> views,
                                       const SurfaceFusionOptions& options,
                                       const ProgressCallback& progress) {
  if (views.empty()) return InvalidArgumentError("surface fusion needs at least one view");
  for (std::size_t v = 0; v < views.size(); ++v) {
    MESHVID_RETURN_IF_ERROR(ValidateMesh(views[v], "view " + std::to_string(v) + " to fuse"));
  }
  if (!(options.spacing >= 0) || !std::isfinite(options.spacing)) {
    return InvalidArgumentError("surface fusion spacing must be finite and >= 0");
  }
  if (!(options.max_triangle_radius > 0) || !(options.max_surface_distance > 0) ||
      !std::isfinite(options.max_triangle_radius) ||
      !std::isfinite(options.max_surface_distance)) {
    return InvalidArgumentError("surface fusion max_triangle_radius and max_surface_distance "
                                "must be finite and > 0");
  }
  if (options.max_points < kMinPoints) {
    return InvalidArgumentError("surface fusion max_points must be at least " +
                                std::to_string(kMinPoints));
  }
  constexpr long kStages = 4;
  if (!ReportProgress(progress, "fusion: points", 0, kStages)) {
    return CancelledError("surface fusion cancelled");
  }
  double area = 0;
  for (const TriangleMesh& view : views) area += SurfaceArea(view);
  const std::vector<OrientedPoint> points =
      Thin(GatherPoints(views), options.max_points, area);
  if (points.size() < kMinPoints) {
    return InvalidArgumentError("surface fusion: the views hold " +
                                std::to_string(points.size()) + " usable points, fewer than " +
                                std::to_string(kMinPoints));
  }
  std::vector<PointWithNormal> samples;
  samples.reserve(points.size());
  for (const OrientedPoint& p : points) {
    samples.emplace_back(Point(p.position.x(), p.position.y(), p.position.z()),
                         Vector(p.normal.x(), p.normal.y(), p.normal.z()));
  }
  const auto point_map = CGAL::First_of_pair_property_map<PointWithNormal>();
  const auto normal_map = CGAL::Second_of_pair_property_map<PointWithNormal>();

  const std::size_t max_vertices =
      options.max_mesher_vertices > 0 ? options.max_mesher_vertices : 10 * options.max_points;
  try {
    // CGAL draws random numbers (mesher seeds, point shuffles) from a thread-local generator
    // it seeds with the time of day: reseed it so the same views give the same surface.
    CGAL::get_default_random() = CGAL::Random(0);
    double spacing = options.spacing;
    if (spacing == 0) {
      spacing = CGAL::compute_average_spacing<CGAL::Sequential_tag>(
          samples, 6, CGAL::parameters::point_map(point_map));
    }
    if (!(spacing > 0)) {
      return InvalidArgumentError("surface fusion: the input points are all at one place");
    }
    if (!ReportProgress(progress, "fusion: poisson", 1, kStages)) {
      return CancelledError("surface fusion cancelled");
    }
    using Poisson = CGAL::Poisson_reconstruction_function<Kernel>;
    Poisson function(samples.begin(), samples.end(), point_map, normal_map);
    if (function.tr().dimension() < 3) {  // CGAL's solver crashes on a flat triangulation
      return InvalidArgumentError("surface fusion: the views' points are all in one plane");
    }
    if (!function.compute_implicit_function()) {
      return InternalError("surface fusion: CGAL could not solve the Poisson equation");
    }
    if (!ReportProgress(progress, "fusion: meshing", 2, kStages)) {
      return CancelledError("surface fusion cancelled");
    }
    // Contouring as in CGAL::poisson_surface_reconstruction_delaunay (facet angle >= 20
    // degrees, size and distance bounds from the options, whose defaults are CGAL's), with
    // the manifold tag so that the surface is closed.
    using Triangulation =
        CGAL::Surface_mesher::Surface_mesh_default_triangulation_3_generator<Kernel>::Type;
    using Complex = CGAL::Surface_mesh_complex_2_in_triangulation_3<Triangulation>;
    using Surface = CGAL::Implicit_surface_3<Kernel, Poisson>;
    const Point inner = function.get_inner_point();
    const double radius = std::sqrt(CGAL::to_double(function.bounding_sphere().squared_radius()));
    const double sphere_radius = 5.0 * radius;
    const double distance = options.max_surface_distance * spacing;
    const double dichotomy_error = distance / 1000.0;
    Surface surface(function, Kernel::Sphere_3(inner, sphere_radius * sphere_radius),
                    dichotomy_error / sphere_radius);
    Triangulation triangulation;
    const BoundedCriteria<Triangulation> criteria(20.0, options.max_triangle_radius * spacing,
                                                  distance, &triangulation, max_vertices);
    Complex complex(triangulation);
    // The mesher seeds itself by shooting random rays from the inner point; a thin surface
    // can escape every one of them, so a few seeds (fixed: the output is deterministic) and
    // more initial rays than CGAL's 20 are tried before giving up.
    for (int seed = 1; seed <= 4 && complex.number_of_facets() == 0; ++seed) {
      triangulation.clear();
      CGAL::get_default_random() = CGAL::Random(seed);
      CGAL::make_surface_mesh(complex, surface, criteria, CGAL::Manifold_tag(), 100 * seed);
    }
    if (triangulation.number_of_vertices() == 0 || complex.number_of_facets() == 0) {
      return InternalError("surface fusion: the Poisson surface is empty");
    }
    if (!ReportProgress(progress, "fusion: cleanup", 3, kStages)) {
      return CancelledError("surface fusion cancelled");
    }
    CGAL::Surface_mesh<Point> surface_mesh;
    CGAL::facets_in_complex_2_to_triangle_mesh(complex, surface_mesh);

    TriangleMesh result;
    result.positions.reserve(surface_mesh.number_of_vertices());
    std::vector<std::uint32_t> index(surface_mesh.num_vertices(), 0);
    for (auto v : surface_mesh.vertices()) {
      const Point& p = surface_mesh.point(v);
      index[v.idx()] = static_cast<std::uint32_t>(result.positions.size());
      result.positions.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                    static_cast<float>(p.z()));
    }
    result.triangles.reserve(surface_mesh.number_of_faces());
    for (auto f : surface_mesh.faces()) {
      Triangle t;
      int c = 0;
      for (auto v : CGAL::vertices_around_face(surface_mesh.halfedge(f), surface_mesh)) {
        if (c < 3) t[c] = index[v.idx()];
        ++c;
      }
      if (c == 3) result.triangles.push_back(t);
    }
    KeepLargestComponent(&result);
    if (result.triangles.empty()) {
      return InternalError("surface fusion: the Poisson surface has no triangle");
    }
    // Outward: a closed surface wound counter-clockwise from outside has positive volume.
    if (SignedVolume6(result) < 0) {
      for (Triangle& t : result.triangles) std::swap(t[1], t[2]);
    }
    Canonicalize(&result);
    result.normals = ComputeVertexNormals(result);
    ReportProgress(progress, "fusion: done", kStages, kStages);
    return result;
  } catch (const MesherTooLarge&) {
    return InvalidArgumentError(
        "surface fusion: the Poisson surface's meshing grew past " +
        std::to_string(max_vertices) +
        " vertices (a level set running far from the data: inconsistent normals or thin open "
        "parts); stopped to bound memory");
  } catch (const std::exception& e) {
    return InternalError(std::string("surface fusion: CGAL failed: ") + e.what());
  }
}

}  // namespace meshvid
