// BD-rate (tools/bench/bd_rate.h) against values known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tools/bench/bd_rate.h"

namespace meshvid {
namespace {

/// Points at `psnrs` with log10(rate) = f(psnr).
template <typename F>
std::vector<RdPoint> Curve(const std::vector<double>& psnrs, F log_rate) {
  std::vector<RdPoint> points;
  for (double p : psnrs) points.push_back({std::pow(10.0, log_rate(p)), p});
  return points;
}

const std::vector<double> kPsnrs = {30, 32.5, 34, 37, 41};

double Reference(double p) { return 3 + 0.08 * p + 0.002 * (p - 35) * (p - 35); }

TEST(BdRateTest, IdenticalCurvesGiveZero) {
  const auto ref = Curve(kPsnrs, Reference);
  for (BdRateMethod method : {BdRateMethod::kPiecewiseCubic, BdRateMethod::kCubicPolynomial}) {
    auto result = BjontegaardDeltaRate(ref, ref, method);
    ASSERT_TRUE(result.ok()) << result.status().ToString();
    EXPECT_NEAR(result->delta, 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(result->psnr_low, 30);
    EXPECT_DOUBLE_EQ(result->psnr_high, 41);
  }
}

TEST(BdRateTest, HalfTheRateEverywhereIsMinusFiftyPercent) {
  const auto ref = Curve(kPsnrs, Reference);
  // Sampled at other PSNRs than the reference: the interpolation must not matter.
  const auto half =
      Curve({31, 33, 36, 39, 44}, [](double p) { return Reference(p) - std::log10(2.0); });
  const auto twice = Curve(kPsnrs, [](double p) { return Reference(p) + std::log10(2.0); });
  auto result = BjontegaardDeltaRate(ref, twice);
  ASSERT_TRUE(result.ok());
  EXPECT_NEAR(result->delta, 1.0, 1e-9);
  // The polynomial fit of a quadratic is exact, so this is exact for VCEG-M33.
  result = BjontegaardDeltaRate(ref, half, BdRateMethod::kCubicPolynomial);
  ASSERT_TRUE(result.ok());
  EXPECT_NEAR(result->delta, -0.5, 1e-9);
  EXPECT_DOUBLE_EQ(result->psnr_low, 31);
  EXPECT_DOUBLE_EQ(result->psnr_high, 41);
  // Piecewise cubic on different samples of a curved function: close, not exact.
  result = BjontegaardDeltaRate(ref, half);
  ASSERT_TRUE(result.ok());
  EXPECT_NEAR(result->delta, -0.5, 2e-3);
}

TEST(BdRateTest, LinearCurvesMatchTheClosedForm) {
  // ref: log10 R = 1 + 0.1 P; test: log10 R = 0.5 + 0.12 P. Over the overlap [31, 36] the
  // mean difference is -0.5 + 0.02 * 33.5 = 0.17, so BD-rate = 10^0.17 - 1.
  const auto ref = Curve({30, 32, 34, 36}, [](double p) { return 1 + 0.1 * p; });
  const auto test = Curve({31, 33, 35, 37}, [](double p) { return 0.5 + 0.12 * p; });
  for (BdRateMethod method : {BdRateMethod::kPiecewiseCubic, BdRateMethod::kCubicPolynomial}) {
    auto result = BjontegaardDeltaRate(ref, test, method);
    ASSERT_TRUE(result.ok());
    EXPECT_NEAR(result->delta, std::pow(10.0, 0.17) - 1, 1e-9);  // +47.91%
    EXPECT_DOUBLE_EQ(result->psnr_low, 31);
    EXPECT_DOUBLE_EQ(result->psnr_high, 36);
  }
}

TEST(BdRateTest, CubicPolynomialIsExactForCubicData) {
  // ref: c(u) = 2 + 0.05u + 0.01u^2 - 0.001u^3, test: 1.8 + 0.07u, u = P - 30 in [0, 9].
  // Integral of test - ref = -1.8 + 0.81 - 2.43 + 1.64025 = -1.77975, mean -0.19775.
  const std::vector<double> psnrs = {30, 33, 36, 39};
  const auto ref = Curve(psnrs, [](double p) {
    const double u = p - 30;
    return 2 + 0.05 * u + 0.01 * u * u - 0.001 * u * u * u;
  });
  const auto test = Curve(psnrs, [](double p) { return 1.8 + 0.07 * (p - 30); });
  auto result = BjontegaardDeltaRate(ref, test, BdRateMethod::kCubicPolynomial);
  ASSERT_TRUE(result.ok());
  EXPECT_NEAR(result->delta, std::pow(10.0, -0.19775) - 1, 1e-9);  // -36.57%
}

TEST(BdRateTest, PiecewiseCubicIntegralMatchesHandComputedSlopes) {
  // x = 0, 1, 2; y = 0, 1, 3: Fritsch-Carlson slopes 0.5, 4/3, 2.5 (scipy's PCHIP).
  const std::vector<double> x = {0, 1, 2}, y = {0, 1, 3};
  EXPECT_NEAR(IntegratePiecewiseCubic(x, y, 0, 1), 0.5 + 0.5 / 12 - (4.0 / 3) / 12, 1e-12);
  EXPECT_NEAR(IntegratePiecewiseCubic(x, y, 1, 2), 2 + (4.0 / 3) / 12 - 2.5 / 12, 1e-12);
  EXPECT_NEAR(IntegratePiecewiseCubic(x, y, 0, 2), 7.0 / 3, 1e-12);
  // A plateau: the monotone interpolant never leaves [0, 1], unlike a cubic polynomial.
  const std::vector<double> xs = {0, 1, 2, 3}, ys = {0, 1, 1, 1};
  EXPECT_LE(IntegratePiecewiseCubic(xs, ys, 1, 3), 2.0 + 1e-12);
  EXPECT_NEAR(IntegratePiecewiseCubic(xs, ys, 1, 3), 2.0, 1e-12);
}

TEST(BdRateTest, PrepareDropsUnusablePointsAndKeepsTheCheapestOfEqualPsnr) {
  const std::vector<RdPoint> points = {{100, 35}, {0, 30},  {50, 35},       {20, NAN},
                                       {10, 31},  {-5, 33}, {INFINITY, 40}, {200, INFINITY}};
  const std::vector<RdPoint> curve = PrepareRdCurve(points);
  ASSERT_EQ(curve.size(), 2u);
  EXPECT_DOUBLE_EQ(curve[0].rate, 10);
  EXPECT_DOUBLE_EQ(curve[1].rate, 50);
  EXPECT_DOUBLE_EQ(curve[1].psnr, 35);
}

TEST(BdRateTest, NoOverlapOrTooFewPointsIsAnError) {
  const auto low = Curve({30, 31, 32, 33}, [](double p) { return p / 10; });
  const auto high = Curve({40, 41, 42, 43}, [](double p) { return p / 10; });
  auto result = BjontegaardDeltaRate(low, high);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(result.status().message().find("do not overlap"), std::string::npos);
  EXPECT_NE(result.status().message().find("30.00..33.00"), std::string::npos);

  const std::vector<RdPoint> one = {{100, 35}};
  EXPECT_FALSE(BjontegaardDeltaRate(low, one).ok());
  const std::vector<RdPoint> three(low.begin(), low.begin() + 3);
  EXPECT_TRUE(BjontegaardDeltaRate(low, three).ok());
  result = BjontegaardDeltaRate(low, three, BdRateMethod::kCubicPolynomial);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.status().message().find("at least 4"), std::string::npos);
}

}  // namespace
}  // namespace meshvid
