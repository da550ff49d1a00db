#include "tools/eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "codec/common/colour_space.h"
#include "codec/common/triangle_distance.h"
#include "tools/eval/sampling.h"
#include "codec/common/point_tree.h"
#include "tools/eval/surface_distance.h"

namespace meshvid {
namespace {

/// One surface prepared for measurement: its samples, their k-d tree, its exact distance.
struct PreparedSurface {
  SurfaceSamples samples;
  std::vector<Eigen::Vector3f> colours;  ///< Y Cb Cr per sample, if the mesh has colours
  PointCloud cloud;
  std::unique_ptr<PointTree> tree;
  std::unique_ptr<SurfaceDistance> surface;
};

/// Errors measured from the samples of one surface to the other.
struct DirectionErrors {
  double d1_mse = 0;
  double d2_mse = 0;
  double exact_rms = 0;
  double exact_max = 0;
  double within_tolerance = 0;  ///< share of samples with exact distance <= tolerance
  Eigen::Vector3d colour_mse = Eigen::Vector3d::Zero();  ///< Y, Cb, Cr (with colour only)
};

/// Each sample's colour as Y Cb Cr: its triangle's vertex colours blended at the sample.
std::vector<Eigen::Vector3f> SampleColours(const TriangleMesh& mesh,
                                           const SurfaceSamples& samples) {
  std::vector<Eigen::Vector3f> colours(samples.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Triangle& t = mesh.triangles[samples.triangles[i]];
      const Eigen::Vector3f w =
          BarycentricWeights(samples.points[i], mesh.positions[t[0]], mesh.positions[t[1]],
                             mesh.positions[t[2]]);
      colours[i] = RgbToYCbCr(BlendColours(mesh.colours, t, w[1], w[2]));
    }
  });
  return colours;
}

Status Prepare(const TriangleMesh& mesh, const char* what, const MetricOptions& options,
               PreparedSurface* out) {
  StatusOr<SurfaceSamples> samples = SampleSurface(mesh, options.samples, options.seed);
  if (!samples.ok()) return samples.status().WithContext(what);
  out->samples = std::move(samples).value();
  out->cloud.points = out->samples.points;
  if (!mesh.colours.empty()) out->colours = SampleColours(mesh, out->samples);
  Status status;
  tbb::parallel_invoke(
      [&] {
        out->tree = std::make_unique<PointTree>(
            3, out->cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
      },
      [&] {
        StatusOr<std::unique_ptr<SurfaceDistance>> surface = SurfaceDistance::Build(mesh);
        if (surface.ok()) {
          out->surface = std::move(surface).value();
        } else {
          status = surface.status().WithContext(what);
        }
      });
  return status;
}

DirectionErrors Measure(const PreparedSurface& from, const PreparedSurface& to,
                        double tolerance) {
  const std::size_t n = from.samples.size();
  const bool colour = !from.colours.empty() && !to.colours.empty();
  std::vector<double> d1(n), d2(n), exact(n);
  std::vector<Eigen::Vector3d> colour_error(colour ? n : 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Eigen::Vector3f& p = from.samples.points[i];
      std::uint32_t nearest = 0;
      float nearest_squared = 0;
      to.tree->knnSearch(p.data(), 1, &nearest, &nearest_squared);
      const Eigen::Vector3d error =
          p.cast<double>() - to.samples.points[nearest].cast<double>();
      d1[i] = error.squaredNorm();
      const double along_normal = error.dot(to.samples.normals[nearest].cast<double>());
      d2[i] = along_normal * along_normal;
      // The nearest sample's triangle is close by: its distance bounds the exact search.
      exact[i] = to.surface->DistanceFrom(p, to.samples.triangles[nearest]);
      if (colour) {
        colour_error[i] =
            (from.colours[i] - to.colours[nearest]).cast<double>().array().square().matrix();
      }
    }
  });
  // Summed in order, so the result does not depend on thread scheduling.
  DirectionErrors e;
  std::size_t within = 0;
  for (std::size_t i = 0; i < n; ++i) {
    e.d1_mse += d1[i];
    e.d2_mse += d2[i];
    e.exact_rms += exact[i] * exact[i];
    e.exact_max = std::max(e.exact_max, exact[i]);
    if (exact[i] <= tolerance) ++within;
    if (colour) e.colour_mse += colour_error[i];
  }
  e.colour_mse /= double(n);
  e.d1_mse /= n;
  e.d2_mse /= n;
  e.exact_rms = std::sqrt(e.exact_rms / n);
  e.within_tolerance = static_cast<double>(within) / n;
  return e;
}

}  // namespace

/// 10 log10(255^2 / mse): the PSNR of 8-bit colour; +infinity when mse is 0.
double ColourPsnr(double mse) {
  if (mse <= 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

double PsnrFromMse(double mse, double peak) {
  if (mse <= 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(3.0 * peak * peak / mse);
}

StatusOr<FrameMetrics> ComputeFrameMetrics(const TriangleMesh& ref, const TriangleMesh& test,
                                           const MetricOptions& options) {
  if (!(options.peak > 0.0) || !std::isfinite(options.peak)) {
    return InvalidArgumentError("the PSNR peak must be a positive number, not " +
                                std::to_string(options.peak));
  }
  if (!(options.coverage_tolerance >= 0.0)) {
    return InvalidArgumentError("the coverage tolerance must be >= 0, not " +
                                std::to_string(options.coverage_tolerance));
  }
  PreparedSurface ref_surface, test_surface;
  Status ref_status, test_status;
  tbb::parallel_invoke(
      [&] { ref_status = Prepare(ref, "reference mesh", options, &ref_surface); },
      [&] { test_status = Prepare(test, "test mesh", options, &test_surface); });
  MESHVID_RETURN_IF_ERROR(ref_status);
  MESHVID_RETURN_IF_ERROR(test_status);

  const DirectionErrors test_to_ref =
      Measure(test_surface, ref_surface, options.coverage_tolerance);
  const DirectionErrors ref_to_test =
      Measure(ref_surface, test_surface, options.coverage_tolerance);

  FrameMetrics m;
  m.d1_mse_test_to_ref = test_to_ref.d1_mse;
  m.d1_mse_ref_to_test = ref_to_test.d1_mse;
  m.d1_mse = std::max(m.d1_mse_test_to_ref, m.d1_mse_ref_to_test);
  m.d1_psnr = PsnrFromMse(m.d1_mse, options.peak);
  m.d2_mse_test_to_ref = test_to_ref.d2_mse;
  m.d2_mse_ref_to_test = ref_to_test.d2_mse;
  m.d2_mse = std::max(m.d2_mse_test_to_ref, m.d2_mse_ref_to_test);
  m.d2_psnr = PsnrFromMse(m.d2_mse, options.peak);
  m.accuracy_rms = test_to_ref.exact_rms;
  m.completeness_rms = ref_to_test.exact_rms;
  m.hausdorff = std::max(test_to_ref.exact_max, ref_to_test.exact_max);
  m.coverage = ref_to_test.within_tolerance;
  m.has_colour = !ref_surface.colours.empty() && !test_surface.colours.empty();
  if (m.has_colour) {
    const Eigen::Vector3d mse = test_to_ref.colour_mse.cwiseMax(ref_to_test.colour_mse);
    m.y_psnr = ColourPsnr(mse[0]);
    m.cb_psnr = ColourPsnr(mse[1]);
    m.cr_psnr = ColourPsnr(mse[2]);
    m.yuv_psnr = (6.0 * m.y_psnr + m.cb_psnr + m.cr_psnr) / 8.0;
    m.y_psnr_test_to_ref = ColourPsnr(test_to_ref.colour_mse[0]);
  }
  return m;
}

}  // namespace meshvid
