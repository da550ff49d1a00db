// Tests of area-weighted surface sampling and the exact closest-point distance.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/test_util.h"
#include "tools/eval/sampling.h"
#include "tools/eval/surface_distance.h"

namespace meshvid {
namespace {

/// Two disjoint triangles of areas 1 and 3.
TriangleMesh TwoTriangles() {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 5}, {3, 0, 5}, {0, 2, 5}};
  mesh.triangles = {Triangle(0, 1, 2), Triangle(3, 4, 5)};
  return mesh;
}

TEST(EvalSamplingTest, SameSeedSamePointsOtherSeedOtherPoints) {
  const TriangleMesh mesh = testing::MakeGridPlane(1.0f, 8);
  const auto a = SampleSurface(mesh, 5000, 7);
  const auto b = SampleSurface(mesh, 5000, 7);
  const auto c = SampleSurface(mesh, 5000, 8);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  EXPECT_EQ(a->points, b->points);
  EXPECT_EQ(a->triangles, b->triangles);
  EXPECT_NE(a->points, c->points);
}

TEST(EvalSamplingTest, CountsPerTriangleFollowArea) {
  const auto samples = SampleSurface(TwoTriangles(), 10000, 1);
  ASSERT_TRUE(samples.ok());
  int in_first = 0;
  for (std::uint32_t t : samples->triangles) in_first += t == 0 ? 1 : 0;
  // Stratified sampling: each triangle gets its area share to within one sample.
  EXPECT_NEAR(in_first, 2500, 1);
  for (std::size_t i = 0; i < samples->size(); ++i) {
    const float z = samples->points[i].z();
    EXPECT_EQ(z, samples->triangles[i] == 0 ? 0.0f : 5.0f);
    EXPECT_EQ(samples->normals[i], Eigen::Vector3f(0, 0, 1));
  }
}

TEST(EvalSamplingTest, CountsFollowAreaOnAnIrregularMesh) {
  // A grid whose columns have widths growing like i: triangle areas differ up to 10x.
  TriangleMesh mesh = testing::MakeGridPlane(1.0f, 10);
  for (Eigen::Vector3f& p : mesh.positions) p.x() = (p.x() + 0.5f) * (p.x() + 0.5f);
  const std::size_t n = 100000;
  const auto samples = SampleSurface(mesh, n, 3);
  ASSERT_TRUE(samples.ok());
  std::vector<int> counts(mesh.triangle_count(), 0);
  for (std::uint32_t t : samples->triangles) ++counts[t];
  const double total_area = SurfaceArea(mesh);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    TriangleMesh one;
    one.positions = mesh.positions;
    one.triangles = {mesh.triangles[t]};
    const double expected = n * SurfaceArea(one) / total_area;
    EXPECT_NEAR(counts[t], expected, 1.0 + 1e-9) << "triangle " << t;
  }
}

TEST(EvalSamplingTest, PointsAreUniformInsideATriangle) {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {Triangle(0, 1, 2)};
  const std::size_t n = 200000;
  const auto samples = SampleSurface(mesh, n, 11);
  ASSERT_TRUE(samples.ok());
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  int below_diagonal_half = 0;  // the sub-triangle x + y < 1/2 has a quarter of the area
  for (const Eigen::Vector3f& p : samples->points) {
    ASSERT_GE(p.x(), 0.0f);
    ASSERT_GE(p.y(), 0.0f);
    ASSERT_LE(p.x() + p.y(), 1.0f + 1e-6f);
    mean += p.cast<double>();
    below_diagonal_half += p.x() + p.y() < 0.5f ? 1 : 0;
  }
  mean /= n;
  // Centroid (1/3, 1/3); the standard deviation of x is sqrt(1/18), so 4 sigma of the mean.
  const double tolerance = 4.0 * std::sqrt(1.0 / 18.0 / n);
  EXPECT_NEAR(mean.x(), 1.0 / 3.0, tolerance);
  EXPECT_NEAR(mean.y(), 1.0 / 3.0, tolerance);
  EXPECT_NEAR(below_diagonal_half / static_cast<double>(n), 0.25,
              4.0 * std::sqrt(0.25 * 0.75 / n));
}

TEST(EvalSamplingTest, RejectsZeroCountAndZeroArea) {
  EXPECT_EQ(SampleSurface(TwoTriangles(), 0, 1).status().code(), StatusCode::kInvalidArgument);
  TriangleMesh flat;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.triangles = {Triangle(0, 1, 2)};
  const auto result = SampleSurface(flat, 10, 1);
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(result.status().message().find("no area"), std::string::npos);
}

TEST(EvalClosestPointTest, CoversInteriorEdgesAndVertices) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_EQ(ClosestPointOnTriangle({0.5, 0.5, 3}, a, b, c), Eigen::Vector3d(0.5, 0.5, 0));
  EXPECT_EQ(ClosestPointOnTriangle({-1, -1, 1}, a, b, c), a);
  EXPECT_EQ(ClosestPointOnTriangle({3, -1, 0}, a, b, c), b);
  EXPECT_EQ(ClosestPointOnTriangle({-1, 5, 0}, a, b, c), c);
  EXPECT_EQ(ClosestPointOnTriangle({1, -4, 0}, a, b, c), Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(ClosestPointOnTriangle({-3, 1, 0}, a, b, c), Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(ClosestPointOnTriangle({2, 2, 0}, a, b, c), Eigen::Vector3d(1, 1, 0));
  // The float version (the decimation's distance bound) agrees.
  const Eigen::Vector3f af(0, 0, 0), bf(2, 0, 0), cf(0, 2, 0);
  EXPECT_EQ(ClosestPointOnTriangle<float>({2, 2, 0}, af, bf, cf), Eigen::Vector3f(1, 1, 0));
  EXPECT_EQ(SquaredDistanceToTriangle<float>({-3, 1, 0}, af, bf, cf), 9.0f);
  EXPECT_EQ(SquaredDistanceToTriangle<float>({0.5f, 0.5f, 3}, af, bf, cf), 9.0f);
  // A degenerate triangle (a segment) gives the distance to the segment.
  EXPECT_EQ(SquaredDistanceToTriangle<float>({1, 1, 0}, af, bf, bf), 1.0f);
}

TEST(EvalSurfaceDistanceTest, ExactDistanceToAPlaneAndItsBorder) {
  const auto surface = SurfaceDistance::Build(testing::MakeGridPlane(1.0f, 4));
  ASSERT_TRUE(surface.ok());
  EXPECT_DOUBLE_EQ((*surface)->Distance({0.1f, 0.2f, 0.25f}), 0.25);
  // Beyond the border x = 0.5: distance to the edge.
  EXPECT_NEAR((*surface)->Distance({1.5f, 0.0f, 0.0f}), 1.0, 1e-7);
  // Starting from any triangle, near or far, gives the same exact answer.
  for (std::uint32_t hint : {0u, 13u, 31u}) {
    EXPECT_DOUBLE_EQ((*surface)->DistanceFrom({0.1f, 0.2f, 0.25f}, hint), 0.25) << hint;
    EXPECT_NEAR((*surface)->DistanceFrom({1.5f, 0.0f, 0.0f}, hint), 1.0, 1e-7) << hint;
  }
}

TEST(EvalSurfaceDistanceTest, RejectsAMeshWithoutTriangles) {
  EXPECT_EQ(SurfaceDistance::Build(TriangleMesh{}).status().code(),
            StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace meshvid
