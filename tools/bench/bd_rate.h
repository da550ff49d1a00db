// Bjontegaard delta rate (BD-rate): the average difference in rate between two
// rate-distortion curves at equal quality, over the quality interval both curves cover
// (G. Bjontegaard, VCEG-M33, 2001; the piecewise-cubic variant of JVET's common test
// conditions and VCEG-AL22). meshvid bench uses it with D1 PSNR as the quality.
#ifndef MESHVID_TOOLS_BENCH_BD_RATE_H_
#define MESHVID_TOOLS_BENCH_BD_RATE_H_

#include <span>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// One rate-distortion point: rate in any positive unit (the same for both curves), quality
/// in dB (higher is better).
struct RdPoint {
  double rate = 0;
  double psnr = 0;
};

/// How log10(rate) is interpolated as a function of PSNR.
enum class BdRateMethod {
  /// Monotone piecewise-cubic Hermite interpolation through every point (Fritsch-Carlson
  /// slopes, as scipy's PchipInterpolator), integrated exactly. Needs >= 2 points per curve;
  /// never overshoots between points. meshvid bench's default.
  kPiecewiseCubic,
  /// VCEG-M33: a least-squares cubic polynomial through all points (exact for 4). Needs >= 4
  /// points per curve.
  kCubicPolynomial,
};

/// The BD-rate of a test curve against a reference curve.
struct BdRateResult {
  /// Average rate change at equal PSNR, as a fraction: -0.5 means the test needs half the
  /// reference's rate, +1 twice it.
  double delta = 0;
  /// The PSNR interval both curves cover, over which the difference is averaged.
  double psnr_low = 0;
  double psnr_high = 0;
};

/// The sorted curve a method interpolates: points ordered by PSNR, non-finite or non-positive
/// points dropped; of points with equal PSNR the lowest rate is kept (the efficient one).
std::vector<RdPoint> PrepareRdCurve(std::span<const RdPoint> points);

/// BD-rate of `test` against `reference`: 10^(mean over [lo, hi] of (log10 R_test -
/// log10 R_ref)) - 1 with [lo, hi] the overlap of both curves' PSNR ranges. Fails with
/// kInvalidArgument if a curve has too few usable points for `method` or the PSNR ranges do
/// not overlap (then the curves cannot be compared at equal quality).
StatusOr<BdRateResult> BjontegaardDeltaRate(std::span<const RdPoint> reference,
                                            std::span<const RdPoint> test,
                                            BdRateMethod method = BdRateMethod::kPiecewiseCubic);

/// The integral over [lo, hi] of the monotone piecewise-cubic interpolant through (x[i], y[i])
/// (x strictly increasing, lo and hi within [x.front(), x.back()]). Exposed for tests.
double IntegratePiecewiseCubic(std::span<const double> x, std::span<const double> y, double lo,
                               double hi);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_BENCH_BD_RATE_H_
