// Tests of the per-frame metrics on surfaces with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/test_util.h"
#include "tools/eval/metrics.h"

namespace meshvid {
namespace {

constexpr std::size_t kSamples = 20000;
constexpr double kPeak = 2.0;

MetricOptions Options(double coverage_tolerance = 0.005) {
  MetricOptions options;
  options.samples = kSamples;
  options.seed = 5;
  options.peak = kPeak;
  options.coverage_tolerance = coverage_tolerance;
  return options;
}

/// A curved, non-planar surface: a bumpy grid.
TriangleMesh BumpySurface() {
  TriangleMesh mesh = testing::MakeGridPlane(1.0f, 20);
  for (Eigen::Vector3f& p : mesh.positions) {
    p.z() = 0.1f * std::sin(6.0f * p.x()) * std::cos(4.0f * p.y());
  }
  mesh.normals.clear();
  return mesh;
}

TEST(EvalMetricsTest, PsnrFromMse) {
  EXPECT_DOUBLE_EQ(PsnrFromMse(3.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(PsnrFromMse(0.03, 1.0), 20.0);
  EXPECT_EQ(PsnrFromMse(0.0, 1.0), std::numeric_limits<double>::infinity());
}

TEST(EvalMetricsTest, MeshAgainstItselfIsExact) {
  const TriangleMesh mesh = BumpySurface();
  const auto m = ComputeFrameMetrics(mesh, mesh, Options());
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  // The same seed samples the same points: point-to-point errors are exactly zero.
  EXPECT_EQ(m->d1_mse, 0.0);
  EXPECT_EQ(m->d2_mse, 0.0);
  EXPECT_EQ(m->d1_psnr, std::numeric_limits<double>::infinity());
  EXPECT_EQ(m->d2_psnr, std::numeric_limits<double>::infinity());
  // Exact distances: zero up to float rounding of the sample positions.
  EXPECT_LT(m->accuracy_rms, 1e-7);
  EXPECT_LT(m->completeness_rms, 1e-7);
  EXPECT_LT(m->hausdorff, 1e-6);
  EXPECT_EQ(m->coverage, 1.0);
}

TEST(EvalMetricsTest, OffsetPlaneGivesTheOffsetEverywhere) {
  const float d = 0.004f;
  // Different tessellations, so the two sample sets do not line up.
  const TriangleMesh ref = testing::MakeGridPlane(1.0f, 10, 0.0f);
  const TriangleMesh test = testing::MakeGridPlane(1.0f, 7, d);
  const auto m = ComputeFrameMetrics(ref, test, Options());
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  const double dd = d;
  EXPECT_NEAR(m->accuracy_rms, dd, 1e-6 * dd);
  EXPECT_NEAR(m->completeness_rms, dd, 1e-6 * dd);
  EXPECT_NEAR(m->hausdorff, dd, 1e-6 * dd);
  // Point-to-plane: the error along the normal is d for every pair.
  EXPECT_NEAR(m->d2_mse, dd * dd, 1e-6 * dd * dd);
  EXPECT_NEAR(m->d2_psnr, 10.0 * std::log10(3.0 * kPeak * kPeak / (dd * dd)), 0.01);
  // Point-to-point adds the in-plane distance to the nearest sample: at least d^2, at most
  // d^2 plus the squared sample spacing h^2 = area / samples.
  const double spacing_squared = 1.0 / kSamples;
  EXPECT_GT(m->d1_mse, dd * dd);
  EXPECT_LT(m->d1_mse, dd * dd + spacing_squared);
  EXPECT_LT(m->d1_psnr, m->d2_psnr);
  EXPECT_EQ(m->coverage, 1.0);  // d = 0.004 < tolerance 0.005
}

TEST(EvalMetricsTest, CoverageIsZeroBeyondTheTolerance) {
  const TriangleMesh ref = testing::MakeGridPlane(1.0f, 10, 0.0f);
  const TriangleMesh test = testing::MakeGridPlane(1.0f, 10, 0.006f);
  const auto m = ComputeFrameMetrics(ref, test, Options(0.005));
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->coverage, 0.0);
  EXPECT_NEAR(m->completeness_rms, 0.006, 1e-6 * 0.006);
}

TEST(EvalMetricsTest, HalfPlaneCoversHalfWithPerfectAccuracy) {
  const TriangleMesh ref = testing::MakeGridPlane(1.0f, 10);
  TriangleMesh half = ref;
  half.triangles.clear();
  for (const Triangle& t : ref.triangles) {
    const float centroid_x =
        (ref.positions[t[0]].x() + ref.positions[t[1]].x() + ref.positions[t[2]].x()) / 3;
    if (centroid_x < 0) half.triangles.push_back(t);
  }
  RemoveUnreferencedVertices(&half);
  const auto m = ComputeFrameMetrics(ref, half, Options(0.005));
  ASSERT_TRUE(m.ok());
  EXPECT_NEAR(m->coverage, 0.5, 0.01);
  EXPECT_LT(m->accuracy_rms, 1e-9);  // every test sample lies on the reference
  // Reference samples at x > 0 are x away from the test's edge: RMS = sqrt(1/24).
  EXPECT_NEAR(m->completeness_rms, std::sqrt(1.0 / 24.0), 0.01 * std::sqrt(1.0 / 24.0));
  // The farthest reference points are the corners at x = 0.5.
  EXPECT_NEAR(m->hausdorff, 0.5, 0.01);
}

TEST(EvalMetricsTest, SameSeedSameResult) {
  const TriangleMesh ref = BumpySurface();
  const TriangleMesh test = testing::MakeGridPlane(1.0f, 13, 0.01f);
  const auto a = ComputeFrameMetrics(ref, test, Options());
  const auto b = ComputeFrameMetrics(ref, test, Options());
  MetricOptions other = Options();
  other.seed = 6;
  const auto c = ComputeFrameMetrics(ref, test, other);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  EXPECT_EQ(a->d1_mse, b->d1_mse);
  EXPECT_EQ(a->d2_mse, b->d2_mse);
  EXPECT_EQ(a->accuracy_rms, b->accuracy_rms);
  EXPECT_EQ(a->completeness_rms, b->completeness_rms);
  EXPECT_EQ(a->hausdorff, b->hausdorff);
  EXPECT_EQ(a->coverage, b->coverage);
  EXPECT_NE(a->d1_mse, c->d1_mse);
  EXPECT_NEAR(a->accuracy_rms, c->accuracy_rms, 0.02 * a->accuracy_rms);
}

TEST(EvalMetricsTest, RejectsBadOptions) {
  const TriangleMesh mesh = testing::MakeGridPlane(1.0f, 2);
  MetricOptions options = Options();
  options.peak = 0;
  EXPECT_EQ(ComputeFrameMetrics(mesh, mesh, options).status().code(),
            StatusCode::kInvalidArgument);
  TriangleMesh empty;
  const auto result = ComputeFrameMetrics(mesh, empty, Options());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(result.status().message().find("test mesh"), std::string::npos);
}

}  // namespace
}  // namespace meshvid
