#include "tools/bench/bd_rate.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>

namespace meshvid {
namespace {

/// Fritsch-Carlson end slope (scipy's PchipInterpolator._edge_case): a three-point estimate,
/// limited so the end segment stays monotone.
double EdgeSlope(double h0, double h1, double d0, double d1) {
  const double m = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
  if (std::signbit(m) != std::signbit(d0) || m == 0 || d0 == 0) return 0;
  if (std::signbit(d0) != std::signbit(d1) && std::abs(m) > 3 * std::abs(d0)) return 3 * d0;
  return m;
}

/// Slopes of the monotone piecewise-cubic interpolant at every knot.
std::vector<double> PchipSlopes(std::span<const double> x, std::span<const double> y) {
  const std::size_t n = x.size();
  std::vector<double> h(n - 1), d(n - 1), m(n, 0.0);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    h[k] = x[k + 1] - x[k];
    d[k] = (y[k + 1] - y[k]) / h[k];
  }
  if (n == 2) {
    m[0] = m[1] = d[0];
    return m;
  }
  for (std::size_t k = 1; k + 1 < n; ++k) {
    if (d[k - 1] * d[k] <= 0) continue;  // local extremum or flat: zero slope
    const double w1 = 2 * h[k] + h[k - 1];
    const double w2 = h[k] + 2 * h[k - 1];
    m[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k]);
  }
  m[0] = EdgeSlope(h[0], h[1], d[0], d[1]);
  m[n - 1] = EdgeSlope(h[n - 2], h[n - 3], d[n - 2], d[n - 3]);
  return m;
}

/// Antiderivatives of the four cubic Hermite basis functions at t in [0, 1].
double IntegralH00(double t) { return t * t * t * t / 2 - t * t * t + t; }
double IntegralH10(double t) { return t * t * t * t / 4 - 2 * t * t * t / 3 + t * t / 2; }
double IntegralH01(double t) { return -t * t * t * t / 2 + t * t * t; }
double IntegralH11(double t) { return t * t * t * t / 4 - t * t * t / 3; }

/// Least-squares cubic through (x, y), as coefficients of (x - centre)^0..3.
Eigen::Vector4d FitCubic(std::span<const double> x, std::span<const double> y, double centre) {
  Eigen::MatrixXd a(x.size(), 4);
  Eigen::VectorXd b(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double u = x[i] - centre;
    a(i, 0) = 1;
    a(i, 1) = u;
    a(i, 2) = u * u;
    a(i, 3) = u * u * u;
    b(i) = y[i];
  }
  return a.colPivHouseholderQr().solve(b);
}

double IntegrateCubic(const Eigen::Vector4d& c, double centre, double lo, double hi) {
  auto antiderivative = [&](double x) {
    const double u = x - centre;
    return c(0) * u + c(1) * u * u / 2 + c(2) * u * u * u / 3 + c(3) * u * u * u * u / 4;
  };
  return antiderivative(hi) - antiderivative(lo);
}

/// The integral of log10(rate) over [lo, hi] for one prepared curve.
double IntegrateLogRate(const std::vector<RdPoint>& curve, BdRateMethod method, double lo,
                        double hi) {
  std::vector<double> x, y;
  for (const RdPoint& p : curve) {
    x.push_back(p.psnr);
    y.push_back(std::log10(p.rate));
  }
  if (method == BdRateMethod::kCubicPolynomial) {
    const double centre = (x.front() + x.back()) / 2;
    return IntegrateCubic(FitCubic(x, y, centre), centre, lo, hi);
  }
  return IntegratePiecewiseCubic(x, y, lo, hi);
}

}  // namespace

std::vector<RdPoint> PrepareRdCurve(std::span<const RdPoint> points) {
  std::vector<RdPoint> curve;
  for (const RdPoint& p : points) {
    if (std::isfinite(p.rate) && std::isfinite(p.psnr) && p.rate > 0) curve.push_back(p);
  }
  std::sort(curve.begin(), curve.end(), [](const RdPoint& a, const RdPoint& b) {
    return a.psnr != b.psnr ? a.psnr < b.psnr : a.rate < b.rate;
  });
  // Equal PSNR: keep the first (lowest rate) of each run.
  curve.erase(std::unique(curve.begin(), curve.end(),
                          [](const RdPoint& a, const RdPoint& b) { return a.psnr == b.psnr; }),
              curve.end());
  return curve;
}

double IntegratePiecewiseCubic(std::span<const double> x, std::span<const double> y, double lo,
                               double hi) {
  const std::vector<double> m = PchipSlopes(x, y);
  double total = 0;
  for (std::size_t k = 0; k + 1 < x.size(); ++k) {
    const double a = std::max(lo, x[k]);
    const double b = std::min(hi, x[k + 1]);
    if (b <= a) continue;
    const double h = x[k + 1] - x[k];
    auto integral = [&](double t) {
      return h * (y[k] * IntegralH00(t) + h * m[k] * IntegralH10(t) + y[k + 1] * IntegralH01(t) +
                  h * m[k + 1] * IntegralH11(t));
    };
    total += integral((b - x[k]) / h) - integral((a - x[k]) / h);
  }
  return total;
}

StatusOr<BdRateResult> BjontegaardDeltaRate(std::span<const RdPoint> reference,
                                            std::span<const RdPoint> test, BdRateMethod method) {
  const std::vector<RdPoint> ref = PrepareRdCurve(reference);
  const std::vector<RdPoint> tst = PrepareRdCurve(test);
  const std::size_t needed = method == BdRateMethod::kCubicPolynomial ? 4 : 2;
  if (ref.size() < needed || tst.size() < needed) {
    return InvalidArgumentError(
        "BD-rate needs at least " + std::to_string(needed) +
        " points with a positive rate and distinct finite PSNR per curve (reference has " +
        std::to_string(ref.size()) + ", test has " + std::to_string(tst.size()) + ")");
  }
  BdRateResult result;
  result.psnr_low = std::max(ref.front().psnr, tst.front().psnr);
  result.psnr_high = std::min(ref.back().psnr, tst.back().psnr);
  if (!(result.psnr_high > result.psnr_low)) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "the PSNR ranges do not overlap (reference %.2f..%.2f dB, test %.2f..%.2f dB)",
                  ref.front().psnr, ref.back().psnr, tst.front().psnr, tst.back().psnr);
    return InvalidArgumentError(text);
  }
  const double width = result.psnr_high - result.psnr_low;
  const double mean_ref = IntegrateLogRate(ref, method, result.psnr_low, result.psnr_high) / width;
  const double mean_tst = IntegrateLogRate(tst, method, result.psnr_low, result.psnr_high) / width;
  result.delta = std::pow(10.0, mean_tst - mean_ref) - 1;
  return result;
}

}  // namespace meshvid
