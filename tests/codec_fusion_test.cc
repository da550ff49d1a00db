// Tests of the automatic base mesh's two steps: DecimateMesh (OpenMesh decimater) and
// FuseRangeMeshes (signed-distance fusion of the views of one frame).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "codec/common/triangle_distance.h"
#include "codec/enc/fusion/decimation.h"
#include "codec/enc/fusion/seen_free_space.h"
#include "codec/enc/fusion/surface_fusion.h"
#include "tests/test_util.h"
#include "tools/io/capture.h"

namespace meshvid {
namespace {

using Eigen::Vector3f;

// A unit-radius icosphere: an icosahedron subdivided `levels` times, projected on the sphere.
TriangleMesh MakeIcosphere(int levels, float radius = 1.0f) {
  const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
  TriangleMesh mesh;
  mesh.positions = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                    {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (const auto& f : faces) mesh.triangles.emplace_back(f[0], f[1], f[2]);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.emplace(key, 0);
      if (inserted) {
        it->second = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.push_back((mesh.positions[a] + mesh.positions[b]) / 2);
      }
      return it->second;
    };
    std::vector<Triangle> finer;
    for (const Triangle& t : mesh.triangles) {
      const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]),
                          ca = midpoint(t[2], t[0]);
      finer.emplace_back(t[0], ab, ca);
      finer.emplace_back(t[1], bc, ab);
      finer.emplace_back(t[2], ca, bc);
      finer.emplace_back(ab, bc, ca);
    }
    mesh.triangles = std::move(finer);
  }
  for (Vector3f& p : mesh.positions) p = p.normalized() * radius;
  return mesh;
}

// Largest distance from a vertex of `from` to the surface of `to` (brute force).
float MaxVertexDistance(const TriangleMesh& from, const TriangleMesh& to) {
  float worst = 0;
  for (const Vector3f& p : from.positions) {
    float best = INFINITY;
    for (const Triangle& t : to.triangles) {
      best = std::min(best, SquaredDistanceToTriangle(p, to.positions[t[0]], to.positions[t[1]],
                                                      to.positions[t[2]]));
    }
    worst = std::max(worst, best);
  }
  return std::sqrt(worst);
}

// True if every directed edge occurs once and its reverse once: closed and oriented.
bool IsClosedAndOriented(const TriangleMesh& mesh) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> directed;
  for (const Triangle& t : mesh.triangles) {
    for (int c = 0; c < 3; ++c) {
      if (!directed.emplace(t[c], t[(c + 1) % 3]).second) return false;
    }
  }
  for (const auto& [a, b] : directed) {
    if (!directed.count({b, a})) return false;
  }
  return true;
}

double SignedVolume(const TriangleMesh& mesh) {
  double volume = 0;
  for (const Triangle& t : mesh.triangles) {
    volume += mesh.positions[t[0]].cast<double>().dot(
                  mesh.positions[t[1]].cast<double>().cross(mesh.positions[t[2]].cast<double>())) /
              6.0;
  }
  return volume;
}

TEST(DecimateMeshTest, ClosedSphereReachesTargetWithinMaxError) {
  const TriangleMesh sphere = MakeIcosphere(5);  // 10242 vertices
  DecimationOptions options;
  options.target_vertices = 500;
  options.max_error = 0.01;
  options.max_normal_deviation_degrees = 30;
  auto decimated = DecimateMesh(sphere, options);
  ASSERT_TRUE(decimated.ok()) << decimated.status().ToString();
  EXPECT_GE(decimated->vertex_count(), 500u);
  EXPECT_LE(decimated->vertex_count(), 515u);
  EXPECT_TRUE(IsClosedAndOriented(*decimated));
  EXPECT_GT(SignedVolume(*decimated), 3.5);  // 4/3 pi = 4.19 for the sphere
  EXPECT_LE(MaxVertexDistance(sphere, *decimated), 0.01f * 1.001f);
  // Halfedge collapses keep vertices where they were: every vertex lies on the sphere.
  for (const Vector3f& p : decimated->positions) EXPECT_NEAR(p.norm(), 1.0f, 1e-6f);
  EXPECT_TRUE(ValidateMesh(*decimated, "decimated").ok());
}

TEST(DecimateMeshTest, MaxErrorStopsEarly) {
  const TriangleMesh sphere = MakeIcosphere(4);  // 2562 vertices
  DecimationOptions options;
  options.target_vertices = 50;
  options.max_error = 0.002;
  auto decimated = DecimateMesh(sphere, options);
  ASSERT_TRUE(decimated.ok()) << decimated.status().ToString();
  EXPECT_GT(decimated->vertex_count(), 200u);  // a 50-vertex sphere deviates by ~0.1
  EXPECT_LT(decimated->vertex_count(), sphere.vertex_count());
  EXPECT_LE(MaxVertexDistance(sphere, *decimated), 0.002f * 1.001f);
}

// An open, bumpy sheet (waves plus noise): the quadrics would flatten it, the distance bound
// stops the collapses that would leave any removed vertex farther from the surface than asked,
// at every bound, and a looser bound leaves fewer vertices.
TEST(DecimateMeshTest, MaxErrorHoldsOnABumpyOpenSheet) {
  TriangleMesh sheet = testing::MakeGridPlane(1.0f, 60);
  std::mt19937 random(7);
  std::normal_distribution<float> noise(0.0f, 0.001f);
  for (Vector3f& p : sheet.positions) {
    p.z() = 0.02f * std::sin(9.0f * p.x()) * std::cos(7.0f * p.y()) + noise(random);
  }
  std::size_t previous = sheet.vertex_count();
  for (const double bound : {0.002, 0.004, 0.008}) {
    DecimationOptions options;
    options.target_vertices = 20;
    options.max_error = bound;
    auto decimated = DecimateMesh(sheet, options);
    ASSERT_TRUE(decimated.ok()) << decimated.status().ToString();
    EXPECT_LE(MaxVertexDistance(sheet, *decimated), static_cast<float>(bound) * 1.001f);
    EXPECT_GT(decimated->vertex_count(), 20u) << bound;  // the bound, not the target, stops it
    EXPECT_LT(decimated->vertex_count(), previous) << bound;
    previous = decimated->vertex_count();
  }
}

TEST(DecimateMeshTest, PlaneToTriangleTargetKeepsOutline) {
  const TriangleMesh plane = testing::MakeGridPlane(1.0f, 100);  // 20000 triangles
  DecimationOptions options;
  options.target_vertices = 0;
  options.target_triangles = 1000;
  auto decimated = DecimateMesh(plane, options);
  ASSERT_TRUE(decimated.ok()) << decimated.status().ToString();
  EXPECT_GE(decimated->triangle_count(), 990u);
  EXPECT_LE(decimated->triangle_count(), 1030u);
  // Boundary planes in the priority keep the square's outline and corners.
  const Eigen::AlignedBox3f box = BoundingBox(*decimated);
  EXPECT_TRUE(box.min().isApprox(Vector3f(-0.5f, -0.5f, 0), 1e-6f)) << box.min().transpose();
  EXPECT_TRUE(box.max().isApprox(Vector3f(0.5f, 0.5f, 0), 1e-6f)) << box.max().transpose();
  EXPECT_NEAR(SurfaceArea(*decimated), 1.0, 1e-4);
  ASSERT_EQ(decimated->normals.size(), decimated->vertex_count());
  for (const Vector3f& n : decimated->normals) EXPECT_GT(n.z(), 0.999f);
}

/// The longest edge of `mesh`.
float LongestEdge(const TriangleMesh& mesh) {
  float longest = 0;
  for (const Triangle& t : mesh.triangles) {
    for (int c = 0; c < 3; ++c) {
      longest = std::max(longest, (mesh.positions[t[c]] - mesh.positions[t[(c + 1) % 3]]).norm());
    }
  }
  return longest;
}

// A flat square decimates, by quadrics alone, into a few triangles spanning it; the edge bound
// stops the collapses that would leave an edge longer than asked, wherever they are.
TEST(DecimateMeshTest, MaxEdgeLengthKeepsEveryEdgeShort) {
  const TriangleMesh plane = testing::MakeGridPlane(1.0f, 40);
  DecimationOptions options;
  options.target_vertices = 4;
  auto unbounded = DecimateMesh(plane, options);
  ASSERT_TRUE(unbounded.ok()) << unbounded.status().ToString();
  EXPECT_GT(LongestEdge(*unbounded), 0.9f);
  options.max_edge_length = 0.2;
  auto bounded = DecimateMesh(plane, options);
  ASSERT_TRUE(bounded.ok()) << bounded.status().ToString();
  EXPECT_LE(LongestEdge(*bounded), 0.2f);
  // At least a 6 x 6 lattice of vertices is needed to cover the square with such edges.
  EXPECT_GE(bounded->vertex_count(), 36u);
  EXPECT_LT(bounded->vertex_count(), plane.vertex_count() / 4);
  EXPECT_NEAR(SurfaceArea(*bounded), 1.0, 1e-4);
  EXPECT_TRUE(ValidateMesh(*bounded, "decimated").ok());
  options.max_edge_length = -1;
  EXPECT_FALSE(DecimateMesh(plane, options).ok());
}

TEST(DecimateMeshTest, LockBoundaryKeepsEveryBoundaryVertex) {
  const TriangleMesh plane = testing::MakeGridPlane(1.0f, 60);  // 240 boundary vertices
  DecimationOptions options;
  options.target_vertices = 300;
  options.lock_boundary = true;
  auto decimated = DecimateMesh(plane, options);
  ASSERT_TRUE(decimated.ok()) << decimated.status().ToString();
  EXPECT_GE(decimated->vertex_count(), 300u);
  EXPECT_LE(decimated->vertex_count(), 310u);
  std::set<std::pair<float, float>> kept;
  for (const Vector3f& p : decimated->positions) kept.emplace(p.x(), p.y());
  int boundary = 0;
  for (const Vector3f& p : plane.positions) {
    if (std::abs(p.x()) < 0.4999f && std::abs(p.y()) < 0.4999f) continue;
    ++boundary;
    EXPECT_TRUE(kept.count({p.x(), p.y()})) << p.transpose();
  }
  EXPECT_EQ(boundary, 240);
}

TEST(DecimateMeshTest, NonManifoldInputIsCleanedNotFatal) {
  TriangleMesh mesh = testing::MakeGridPlane(1.0f, 10);
  mesh.normals.clear();
  const Triangle first = mesh.triangles[0];
  mesh.triangles.push_back(first);                                   // duplicate
  mesh.triangles.emplace_back(first[0], first[1], first[1]);         // degenerate
  mesh.positions.emplace_back(0.0f, 0.0f, 1.0f);                     // a fin on an edge
  mesh.triangles.emplace_back(first[1], first[0],
                              static_cast<std::uint32_t>(mesh.positions.size() - 1));
  mesh.positions.emplace_back(5.0f, 5.0f, 5.0f);                     // unreferenced
  DecimationOptions options;
  options.target_vertices = 30;
  auto decimated = DecimateMesh(mesh, options);
  ASSERT_TRUE(decimated.ok()) << decimated.status().ToString();
  EXPECT_TRUE(ValidateMesh(*decimated, "decimated").ok());
  EXPECT_LE(decimated->vertex_count(), 32u);
  for (const Vector3f& p : decimated->positions) EXPECT_LT(p.norm(), 2.0f);
}

TEST(DecimateMeshTest, InvalidInputFails) {
  DecimationOptions options;
  EXPECT_FALSE(DecimateMesh(TriangleMesh{}, options).ok());
  TriangleMesh bad = testing::MakeGridPlane(1.0f, 4);
  bad.triangles.emplace_back(0, 1, 999);
  EXPECT_FALSE(DecimateMesh(bad, options).ok());
  const TriangleMesh plane = testing::MakeGridPlane(1.0f, 4);
  options.target_vertices = 0;
  EXPECT_EQ(DecimateMesh(plane, options).status().code(), StatusCode::kInvalidArgument);
  options.target_vertices = 10;
  options.max_error = -1;
  EXPECT_EQ(DecimateMesh(plane, options).status().code(), StatusCode::kInvalidArgument);
  options.max_error = 0;
  options.max_normal_deviation_degrees = 200;
  EXPECT_EQ(DecimateMesh(plane, options).status().code(), StatusCode::kInvalidArgument);
}

// A range image of the sphere |p| = radius seen from `sensor` (looking at the origin): a
// grid of rays intersected with the sphere, depth noise of `noise` along each ray,
// triangulated cell by cell and wound counter-clockwise seen from the sensor.
TriangleMesh MakeSphereRangeView(const Vector3f& sensor, float radius, int n, float noise,
                                 std::mt19937* random) {
  const Vector3f forward = -sensor.normalized();
  const Vector3f helper = std::abs(forward.y()) < 0.9f ? Vector3f::UnitY() : Vector3f::UnitX();
  const Vector3f right = forward.cross(helper).normalized();
  const Vector3f up = right.cross(forward);
  const float half = std::tan(std::asin(radius / sensor.norm())) * 1.05f;
  std::normal_distribution<float> gauss(0.0f, noise);
  TriangleMesh mesh;
  std::vector<std::int64_t> index(n * n, -1);
  for (int row = 0; row < n; ++row) {
    for (int col = 0; col < n; ++col) {
      const float u = half * (2.0f * col / (n - 1) - 1), v = half * (1 - 2.0f * row / (n - 1));
      const Vector3f ray = (forward + u * right + v * up).normalized();
      const float b = sensor.dot(ray);
      const float disc = b * b - (sensor.squaredNorm() - radius * radius);
      if (disc <= 0) continue;
      const float depth = -b - std::sqrt(disc);
      index[row * n + col] = static_cast<std::int64_t>(mesh.positions.size());
      mesh.positions.push_back(sensor + ray * (depth + gauss(*random)));
    }
  }
  auto add = [&](int a, int b, int c) {
    if (index[a] < 0 || index[b] < 0 || index[c] < 0) return;
    Triangle t(index[a], index[b], index[c]);
    const Vector3f& p = mesh.positions[t[0]];
    const Vector3f normal = (mesh.positions[t[1]] - p).cross(mesh.positions[t[2]] - p);
    if (normal.dot(sensor - p) < 0) std::swap(t[1], t[2]);
    mesh.triangles.push_back(t);
  };
  for (int row = 0; row + 1 < n; ++row) {
    for (int col = 0; col + 1 < n; ++col) {
      const int a = row * n + col, b = a + 1, c = a + n, d = c + 1;
      add(a, c, d);
      add(a, d, b);
    }
  }
  RemoveUnreferencedVertices(&mesh);
  return mesh;
}

// Views of a sphere of radius `radius` from sensors at distance 0.7 along `directions`.
std::vector<TriangleMesh> SphereViews(const std::vector<Vector3f>& directions, float radius,
                                      float noise) {
  std::mt19937 random(7);
  std::vector<TriangleMesh> views;
  for (const Vector3f& direction : directions) {
    views.push_back(MakeSphereRangeView(direction.normalized() * 0.7f, radius, 90, noise,
                                        &random));
  }
  return views;
}

TEST(FuseRangeMeshesTest, SphereSeenFromSixSidesClosesOutward) {
  constexpr float kRadius = 0.2f;
  const std::vector<TriangleMesh> views = SphereViews(
      {Vector3f::UnitX(), -Vector3f::UnitX(), Vector3f::UnitY(), -Vector3f::UnitY(),
       Vector3f::UnitZ(), -Vector3f::UnitZ()},
      kRadius, 0.0005f);
  SurfaceFusionOptions options;
  options.max_points = 15000;
  int calls = 0;
  auto fused = FuseRangeMeshes(views, options, [&calls](std::string_view, long, long) {
    ++calls;
    return true;
  });
  ASSERT_TRUE(fused.ok()) << fused.status().ToString();
  EXPECT_GT(calls, 2);
  EXPECT_GT(fused->vertex_count(), 500u);
  EXPECT_TRUE(IsClosedAndOriented(*fused));
  const double sphere_volume = 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius;
  EXPECT_NEAR(SignedVolume(*fused), sphere_volume, 0.05 * sphere_volume);
  ASSERT_EQ(fused->normals.size(), fused->vertex_count());
  for (std::size_t v = 0; v < fused->vertex_count(); ++v) {
    const Vector3f& p = fused->positions[v];
    EXPECT_GT(fused->normals[v].dot(p.normalized()), 0.5f);  // outward
    EXPECT_NEAR(p.norm(), kRadius, 0.002f) << p.transpose();  // about the views' noise
  }
  // The same views give the same surface, vertex for vertex.
  auto again = FuseRangeMeshes(views, options);
  ASSERT_TRUE(again.ok()) << again.status().ToString();
  EXPECT_EQ(again->positions, fused->positions);
  EXPECT_EQ(again->triangles, fused->triangles);
  // The voxel bound coarsens the surface instead of failing.
  options.max_voxels = 20000;
  auto bounded = FuseRangeMeshes(views, options);
  ASSERT_TRUE(bounded.ok()) << bounded.status().ToString();
  EXPECT_LT(bounded->vertex_count(), fused->vertex_count() / 2);
  EXPECT_GT(bounded->vertex_count(), 50u);
}

TEST(FuseRangeMeshesTest, HalfSeenSphereStaysOpenWhereNoViewLooks) {
  constexpr float kRadius = 0.2f;
  // Three views on a frontal arc: the back of the sphere is never seen.
  std::vector<Vector3f> directions;
  for (int k = -1; k <= 1; ++k) directions.emplace_back(std::sin(0.6f * k), 0, std::cos(0.6f * k));
  const std::vector<TriangleMesh> views = SphereViews(directions, kRadius, 0.0005f);
  auto fused = FuseRangeMeshes(views);
  ASSERT_TRUE(fused.ok()) << fused.status().ToString();
  EXPECT_GT(testing::BoundaryEdgeCount(*fused), 20u);
  for (const Vector3f& p : fused->positions) {
    EXPECT_NEAR(p.norm(), kRadius, 0.002f) << p.transpose();
    // Seen by some view: at most a few degrees past a view's horizon.
    float best = -1;
    for (const Vector3f& d : directions) best = std::max(best, p.normalized().dot(d));
    EXPECT_GT(best, -0.1f) << "a sheet where no view looks: " << p.transpose();
  }
}

TEST(FuseRangeMeshesTest, OpenPlaneStaysOpenWithItsBoundary) {
  // A 0.4 m square sheet sampled every 4 mm, seen from one side.
  std::vector<TriangleMesh> views = {testing::MakeGridPlane(0.4f, 100)};
  auto fused = FuseRangeMeshes(views);
  ASSERT_TRUE(fused.ok()) << fused.status().ToString();
  EXPECT_GT(testing::BoundaryEdgeCount(*fused), 100u);
  EXPECT_NEAR(SurfaceArea(*fused), 0.16, 0.16 * 0.05);
  const Eigen::AlignedBox3f box = BoundingBox(*fused);
  EXPECT_LT(box.sizes().z(), 1e-4f);
  EXPECT_LT(box.sizes().x(), 0.4f + 0.01f);  // ends within a few voxels of the data's edge
  for (const Vector3f& n : fused->normals) EXPECT_GT(n.z(), 0.99f);
}

// How far the farthest triangle centre of `mesh` lies outside the square |x|, |y| <= half.
float FarthestCentreOutsideSquare(const TriangleMesh& mesh, float half) {
  float farthest = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vector3f centre =
        (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3;
    const float dx = std::max(0.0f, std::abs(centre.x()) - half);
    const float dy = std::max(0.0f, std::abs(centre.y()) - half);
    farthest = std::max(farthest, std::hypot(dx, dy));
  }
  return farthest;
}

TEST(FuseRangeMeshesTest, ThinnedInputEndsNearTheDataWithMaxExtension) {
  // The 0.4 m sheet sampled every 4 mm, fused from 400 points: a voxel of about 20 mm, which
  // the volume's support lets run on past the sheet's edge.
  std::vector<TriangleMesh> views = {testing::MakeGridPlane(0.4f, 100)};
  SurfaceFusionOptions options;
  options.max_points = 400;
  auto coarse = FuseRangeMeshes(views, options);
  ASSERT_TRUE(coarse.ok()) << coarse.status().ToString();
  options.max_extension_spacings = 1.5;
  auto trimmed = FuseRangeMeshes(views, options);
  ASSERT_TRUE(trimmed.ok()) << trimmed.status().ToString();
  const float spacing = 0.4f / 100;
  EXPECT_GT(FarthestCentreOutsideSquare(*coarse, 0.2f), 3 * spacing);
  EXPECT_LE(FarthestCentreOutsideSquare(*trimmed, 0.2f), 1.5f * spacing + 1e-5f);
  EXPECT_NEAR(SurfaceArea(*trimmed), 0.16, 0.16 * 0.05);
  EXPECT_GT(testing::BoundaryEdgeCount(*trimmed), 20u);
  options.max_extension_spacings = -1;
  EXPECT_EQ(FuseRangeMeshes(views, options).status().code(), StatusCode::kInvalidArgument);
}

TEST(FuseRangeMeshesTest, MaxExtensionTrimsFromTheBoundaryOnly) {
  // The sheet with no samples within 14 mm of its centre: the coarse volume bridges the gap,
  // and the trim, which peels from the outer edge inwards, leaves the bridge in place.
  TriangleMesh sheet = testing::MakeGridPlane(0.4f, 100);
  std::erase_if(sheet.triangles, [&](const Triangle& t) {
    for (int c = 0; c < 3; ++c) {
      if (sheet.positions[t[c]].head<2>().norm() < 0.014f) return true;
    }
    return false;
  });
  sheet.normals.clear();
  RemoveUnreferencedVertices(&sheet);
  std::vector<TriangleMesh> views = {sheet};
  SurfaceFusionOptions options;
  options.max_points = 400;
  options.max_extension_spacings = 1.5;
  auto trimmed = FuseRangeMeshes(views, options);
  ASSERT_TRUE(trimmed.ok()) << trimmed.status().ToString();
  auto covers_centre = [](const TriangleMesh& mesh) {
    for (const Triangle& t : mesh.triangles) {
      const Eigen::Vector2f a = mesh.positions[t[0]].head<2>(), b = mesh.positions[t[1]].head<2>(),
                            c = mesh.positions[t[2]].head<2>();
      auto side = [](const Eigen::Vector2f& p, const Eigen::Vector2f& q) {
        return p.x() * q.y() - p.y() * q.x();  // sign of the origin against the edge p -> q
      };
      const float s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
      if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return true;
    }
    return false;
  };
  EXPECT_TRUE(covers_centre(*trimmed));
  EXPECT_LE(FarthestCentreOutsideSquare(*trimmed, 0.2f), 1.5f * 0.004f + 1e-5f);
}

// The camera 1 m above the 0.4 m sheet of MakeGridPlane: one pixel per 4 mm sample there.
ViewCalibration CameraAboveSheet() { return testing::CameraLookingAtOrigin({0, 0, 1}, 200, 250); }

TEST(SeenFreeSpaceTest, InFrontOfTheDataOrPastItsEdgeWhereTheCameraFacesTheSurface) {
  const std::vector<TriangleMesh> views = {testing::MakeGridPlane(0.4f, 100)};
  const std::vector<ViewCalibration> cameras = {CameraAboveSheet()};
  const SeenFreeSpace free_space(views, cameras, /*margin_pixels=*/0);
  ASSERT_EQ(free_space.view_count(), 1);
  const Vector3f up = Vector3f::UnitZ();
  EXPECT_TRUE(free_space.Contains({0.05f, 0.02f, 0.05f}, up, 0.01f));   // 5 cm in front
  EXPECT_FALSE(free_space.Contains({0.05f, 0.02f, 0.005f}, up, 0.01f));  // within tolerance
  EXPECT_FALSE(free_space.Contains({0.05f, 0.02f, -0.05f}, up, 0.01f));  // behind: occluded
  EXPECT_FALSE(free_space.Contains({0.199f, 0, 0}, up, 0.01f));          // on the data
  EXPECT_TRUE(free_space.Contains({0.21f, 0, 0}, up, 0.01f));            // past its edge
  // Past the edge, but the camera would see that surface at 81 degrees: it does not speak.
  const Vector3f grazing = Vector3f(1, 0, 0.05f).normalized();
  EXPECT_FALSE(free_space.Contains({0.21f, 0, 0}, grazing, 0.01f));
  EXPECT_FALSE(free_space.Contains({0, 0, 1.5f}, up, 0.01f));  // behind the camera
  EXPECT_FALSE(free_space.Contains({5, 0, 0}, up, 0.01f));     // outside its image
  // Judged across the image too, a point past the edge by less than the tolerance (10 mm,
  // 2.5 pixels there) is not in free space; 3 cm past it, or 5 cm in front of the edge, is.
  using Verdict = SeenFreeSpace::Verdict;
  EXPECT_EQ(free_space.Judge({0.21f, 0, 0}, up, 0.01f, /*across_too=*/true), Verdict::kSeen);
  EXPECT_EQ(free_space.Judge({0.23f, 0, 0}, up, 0.01f, true), Verdict::kSeenThrough);
  EXPECT_EQ(free_space.Judge({0.21f, 0, 0.05f}, up, 0.01f, true), Verdict::kSeenThrough);
  // A margin of 2 pixels (8 mm there) keeps the first points past the edge.
  const SeenFreeSpace with_margin(views, cameras, 2);
  EXPECT_FALSE(with_margin.Contains({0.205f, 0, 0}, up, 0.01f));
  EXPECT_TRUE(with_margin.Contains({0.215f, 0, 0}, up, 0.01f));
  // Blocks of 2 x 2 pixels keep their nearest depth: the edge moves out by up to a pixel.
  const SeenFreeSpace blocks(views, cameras, 0, 0.5f, 2);
  EXPECT_TRUE(blocks.Contains({0.05f, 0.02f, 0.05f}, up, 0.01f));
  EXPECT_FALSE(blocks.Contains({0.05f, 0.02f, -0.05f}, up, 0.01f));
  EXPECT_TRUE(blocks.Contains({0.215f, 0, 0}, up, 0.01f));
  // Judged by the cameras that face a point inside their image only.
  EXPECT_EQ(free_space.Judge({0.05f, 0.02f, 0}, up, 0.01f), SeenFreeSpace::Verdict::kSeen);
  EXPECT_EQ(free_space.Judge({0.21f, 0, 0}, grazing, 0.01f), SeenFreeSpace::Verdict::kUnjudged);
  EXPECT_EQ(free_space.Judge({5, 0, 0}, up, 0.01f), SeenFreeSpace::Verdict::kUnjudged);
  // A surface facing away from the camera (the far side of a part whose near side was lost
  // at a grazing angle) is not judged.
  EXPECT_EQ(free_space.Judge({0.21f, 0, 0}, -up, 0.01f), SeenFreeSpace::Verdict::kUnjudged);
  // The gap is measured along the normal: 5 cm above the sheet, seen at 55 degrees from its
  // normal, is 8.7 cm along the ray.
  const float angle = 55 * static_cast<float>(M_PI) / 180;
  const std::vector<ViewCalibration> oblique = {
      testing::CameraLookingAtOrigin({std::sin(angle), 0, std::cos(angle)}, 200, 250)};
  const SeenFreeSpace seen_obliquely(views, oblique, 0);
  EXPECT_TRUE(seen_obliquely.Contains({0, 0, 0.05f}, up, 0.045f));
  EXPECT_FALSE(seen_obliquely.Contains({0, 0, 0.05f}, up, 0.055f));
}

TEST(SeenFreeSpaceTest, ViewsWithoutIntrinsicsOrPoseTakeNoPart) {
  const std::vector<TriangleMesh> views = {testing::MakeGridPlane(0.4f, 100),
                                           testing::MakeGridPlane(0.4f, 100)};
  std::vector<ViewCalibration> cameras = {CameraAboveSheet(), CameraAboveSheet()};
  cameras[0].intrinsics.reset();
  cameras[1].has_extrinsics = false;
  const SeenFreeSpace free_space(views, cameras);
  EXPECT_EQ(free_space.view_count(), 0);
  EXPECT_FALSE(free_space.Contains({0, 0, 0.5f}, Vector3f::UnitZ(), 0));
  EXPECT_EQ(SeenFreeSpace(views, {}).view_count(), 0);
}

TEST(FuseRangeMeshesTest, CamerasEndAThinnedSheetAtItsSeenEdge) {
  // As ThinnedInputEndsNearTheDataWithMaxExtension: the trim alone leaves the sheet up to 1.5
  // samples too wide; the camera saw the background there.
  std::vector<TriangleMesh> views = {testing::MakeGridPlane(0.4f, 100)};
  SurfaceFusionOptions options;
  options.max_points = 400;
  options.max_extension_spacings = 1.5;
  auto trimmed = FuseRangeMeshes(views, options);
  ASSERT_TRUE(trimmed.ok()) << trimmed.status().ToString();
  options.view_cameras = {CameraAboveSheet()};
  auto seen = FuseRangeMeshes(views, options);
  ASSERT_TRUE(seen.ok()) << seen.status().ToString();
  const float spacing = 0.4f / 100;
  EXPECT_GT(FarthestCentreOutsideSquare(*trimmed, 0.2f), 0.9f * spacing);
  EXPECT_LE(FarthestCentreOutsideSquare(*seen, 0.2f), 0.6f * spacing)
      << FarthestCentreOutsideSquare(*seen, 0.2f) / spacing;
  EXPECT_NEAR(SurfaceArea(*seen), 0.16, 0.16 * 0.05);
  options.free_space_margin_pixels = -1;
  EXPECT_EQ(FuseRangeMeshes(views, options).status().code(), StatusCode::kInvalidArgument);
}

TEST(FuseRangeMeshesTest, CamerasKeepAClosedBodyTurningOutOfSight) {
  // A sphere seen by one camera: past its silhouette the fused surface turns away from the
  // camera, behind what it saw or at grazing angles, so nothing there is cut.
  const Vector3f sensor(0, 0, 0.7f);
  std::mt19937 random(3);
  const std::vector<TriangleMesh> views = {MakeSphereRangeView(sensor, 0.2f, 160, 0, &random)};
  SurfaceFusionOptions options;
  options.max_points = 2000;
  options.max_extension_spacings = 1.5;
  auto trimmed = FuseRangeMeshes(views, options);
  ASSERT_TRUE(trimmed.ok()) << trimmed.status().ToString();
  options.view_cameras = {testing::CameraLookingAtOrigin(sensor, 300, 450)};
  auto seen = FuseRangeMeshes(views, options);
  ASSERT_TRUE(seen.ok()) << seen.status().ToString();
  EXPECT_GT(SurfaceArea(*seen), 0.99 * SurfaceArea(*trimmed));
}

TEST(FuseRangeMeshesTest, ThinPlateFusesAsTwoSheets) {
  // Two faces 5 mm apart, seen from above and from below, sampled every 1 mm.
  TriangleMesh top = testing::MakeGridPlane(0.1f, 100, 0.0025f);
  TriangleMesh bottom = testing::MakeGridPlane(0.1f, 100, -0.0025f);
  for (Vector3f& n : bottom.normals) n = -n;
  for (Triangle& t : bottom.triangles) std::swap(t[1], t[2]);
  const std::vector<TriangleMesh> views = {top, bottom};
  auto fused = FuseRangeMeshes(views);
  ASSERT_TRUE(fused.ok()) << fused.status().ToString();
  std::size_t up = 0, down = 0;
  for (std::size_t v = 0; v < fused->vertex_count(); ++v) {
    const Vector3f& p = fused->positions[v];
    const float z = p.z();
    if (std::abs(p.x()) > 0.045f || std::abs(p.y()) > 0.045f) continue;  // away from the rim
    EXPECT_NEAR(std::abs(z), 0.0025f, 0.0006f) << p.transpose();
    if (z > 0) {
      EXPECT_GT(fused->normals[v].z(), 0.9f);
      ++up;
    } else {
      EXPECT_LT(fused->normals[v].z(), -0.9f);
      ++down;
    }
  }
  EXPECT_GT(up, 1000u);
  EXPECT_GT(down, 1000u);
}

TEST(FuseRangeMeshesTest, SheetSeenFromBothSidesFusesAsOneOpenSheet) {
  // A cloth-like sheet with no thickness, seen from above and from below (a ring of sensors):
  // the two sides' distances cancel unless one side is kept.
  TriangleMesh above = testing::MakeGridPlane(0.4f, 100);
  TriangleMesh below = above;
  for (Vector3f& n : below.normals) n = -n;
  for (Triangle& t : below.triangles) std::swap(t[1], t[2]);
  for (Vector3f& p : below.positions) p += Vector3f(0.002f, 0.001f, 0);  // other samples
  const std::vector<TriangleMesh> views = {above, below};
  auto fused = FuseRangeMeshes(views);
  ASSERT_TRUE(fused.ok()) << fused.status().ToString();
  EXPECT_GT(testing::BoundaryEdgeCount(*fused), 100u);
  EXPECT_NEAR(SurfaceArea(*fused), 0.16, 0.16 * 0.05);  // one sheet, not two
  for (const Vector3f& p : fused->positions) EXPECT_LT(std::abs(p.z()), 0.001f) << p.transpose();
}

TEST(FuseRangeMeshesTest, InvalidInputFails) {
  EXPECT_EQ(FuseRangeMeshes({}).status().code(), StatusCode::kInvalidArgument);
  std::vector<TriangleMesh> tiny = {testing::MakeGridPlane(1.0f, 2)};
  EXPECT_EQ(FuseRangeMeshes(tiny).status().code(), StatusCode::kInvalidArgument);
  // 441 points on one line: no area, no surface.
  std::vector<TriangleMesh> line = {testing::MakeGridPlane(1.0f, 20)};
  for (Vector3f& p : line[0].positions) p.y() = 0;
  const auto degenerate = FuseRangeMeshes(line);
  EXPECT_EQ(degenerate.status().code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(degenerate.status().message().empty());
  std::vector<TriangleMesh> bad = {testing::MakeGridPlane(1.0f, 20)};
  bad[0].triangles.emplace_back(0, 1, 100000);
  EXPECT_FALSE(FuseRangeMeshes(bad).ok());
  std::vector<TriangleMesh> views = {testing::MakeGridPlane(1.0f, 20)};
  SurfaceFusionOptions options;
  options.spacing = -1;
  EXPECT_EQ(FuseRangeMeshes(views, options).status().code(), StatusCode::kInvalidArgument);
  options = {};
  options.truncation_voxels = 0;
  EXPECT_EQ(FuseRangeMeshes(views, options).status().code(), StatusCode::kInvalidArgument);
}

TEST(FuseRangeMeshesTest, StanfordBunnyGivesOneOutwardSurfaceNearTheScans) {
  MESHVID_REQUIRE_SHARED_DATA();
  auto capture = CaptureSequence::Open(shared_data + "/bunny-range/bun.conf");
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  auto views = (*capture)->LoadFrame(0);
  ASSERT_TRUE(views.ok()) << views.status().ToString();
  ASSERT_EQ(views->size(), 10u);
  SurfaceFusionOptions options;
  options.max_points = 20000;
  auto fused = FuseRangeMeshes(*views, options);
  ASSERT_TRUE(fused.ok()) << fused.status().ToString();
  EXPECT_GT(SignedVolume(*fused), 0);  // outward (the scans leave only the base open)
  EXPECT_GT(fused->vertex_count(), 1000u);
  EXPECT_LT(fused->vertex_count(), 200000u);
  // The bunny is about 0.15 x 0.15 x 0.12 m; the surface stays near the scans' box.
  Eigen::AlignedBox3f scans;
  for (const TriangleMesh& view : *views) scans.extend(BoundingBox(view));
  const Eigen::AlignedBox3f box = BoundingBox(*fused);
  EXPECT_TRUE(scans.sizes().isApprox(box.sizes(), 0.1f))
      << scans.sizes().transpose() << " vs " << box.sizes().transpose();
}

}  // namespace
}  // namespace meshvid
