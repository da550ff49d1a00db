// Per-frame geometric error of a test surface against a reference (ground-truth) surface:
// MPEG pc_error style D1/D2 PSNR on dense samples, and exact point-to-surface accuracy,
// completeness, Hausdorff distance and coverage.
#ifndef MESHVID_TOOLS_EVAL_METRICS_H_
#define MESHVID_TOOLS_EVAL_METRICS_H_

#include <cstddef>
#include <cstdint>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// How one frame is measured.
struct MetricOptions {
  /// Area-weighted samples drawn on each of the two surfaces.
  std::size_t samples = 200000;
  /// Sampling seed; the same seed samples a mesh identically, so a mesh against itself has
  /// D1 = D2 = 0 exactly.
  std::uint64_t seed = 1;
  /// PSNR peak p (the ground truth's bounding-box diagonal over the sequence); must be > 0.
  double peak = 1.0;
  /// A reference sample is covered when the test surface is within this distance; >= 0.
  double coverage_tolerance = 0.0;
};

/// The metrics of one frame. Distances are in the meshes' units. "test->ref" measures from
/// samples of the test surface to the reference; "ref->test" the other way.
struct FrameMetrics {
  int frame = 0;
  double d1_mse_test_to_ref = 0;  ///< mean squared distance to the nearest sample
  double d1_mse_ref_to_test = 0;
  double d1_mse = 0;              ///< symmetric: the larger direction
  double d1_psnr = 0;             ///< 10 log10(3 p^2 / d1_mse); +inf when d1_mse is 0
  double d2_mse_test_to_ref = 0;  ///< as D1, the error projected on the nearest sample's normal
  double d2_mse_ref_to_test = 0;
  double d2_mse = 0;
  double d2_psnr = 0;
  double accuracy_rms = 0;        ///< RMS exact distance test samples -> reference surface
  double completeness_rms = 0;    ///< RMS exact distance reference samples -> test surface
  double hausdorff = 0;           ///< largest exact distance, either direction
  double coverage = 0;            ///< share of reference samples within the tolerance
  /// Colour, when both meshes have vertex colours (MPEG pc_error's attribute PSNR): each
  /// sample's colour (its triangle's vertex colours blended at it) against its nearest
  /// sample's on the other surface, in full-range BT.709 Y Cb Cr; per channel the larger
  /// direction's MSE; PSNR 10 log10(255^2 / MSE) (+inf at 0).
  bool has_colour = false;
  double y_psnr = 0;
  double cb_psnr = 0;
  double cr_psnr = 0;
  /// (6 Y + Cb + Cr) / 8 of the three PSNRs, as MPEG weighs them.
  double yuv_psnr = 0;
  /// Y PSNR of the test surface's colour against the reference's (test->ref only): the
  /// colour where the test surface is, whatever the reference has that it lacks.
  double y_psnr_test_to_ref = 0;
};

/// 10 log10(3 peak^2 / mse), the pc_error PSNR; +infinity when mse is 0.
double PsnrFromMse(double mse, double peak);

/// Measures `test` against `ref`. Both must have positive area. Runs in parallel (TBB); the
/// result depends only on the meshes and the options.
StatusOr<FrameMetrics> ComputeFrameMetrics(const TriangleMesh& ref, const TriangleMesh& test,
                                           const MetricOptions& options);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_EVAL_METRICS_H_
