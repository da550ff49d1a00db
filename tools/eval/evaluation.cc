#include "tools/eval/evaluation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "tools/eval/sampling.h"

namespace meshvid {

StatusOr<double> SequenceBoundingBoxDiagonal(MeshSequence& sequence,
                                             const ProgressCallback& progress) {
  const int count = sequence.frame_count();
  if (count <= 0) {
    return InvalidArgumentError(sequence.description() + ": the sequence has no frames");
  }
  Eigen::AlignedBox3f box;
  for (int t = 0; t < count; ++t) {
    if (!ReportProgress(progress, "bounds", t, count)) {
      return CancelledError("evaluation cancelled");
    }
    StatusOr<TriangleMesh> mesh = sequence.Frame(t);
    if (!mesh.ok()) {
      return mesh.status().WithContext(sequence.description() + ", frame " + std::to_string(t));
    }
    box.extend(BoundingBox(*mesh));
  }
  ReportProgress(progress, "bounds", count, count);
  return static_cast<double>(box.diagonal().cast<double>().norm());
}

FrameMetrics MeanFrameMetrics(const std::vector<FrameMetrics>& frames, double peak) {
  FrameMetrics mean;
  mean.frame = -1;
  if (frames.empty()) return mean;
  for (const FrameMetrics& f : frames) {
    mean.d1_mse_test_to_ref += f.d1_mse_test_to_ref;
    mean.d1_mse_ref_to_test += f.d1_mse_ref_to_test;
    mean.d1_mse += f.d1_mse;
    mean.d2_mse_test_to_ref += f.d2_mse_test_to_ref;
    mean.d2_mse_ref_to_test += f.d2_mse_ref_to_test;
    mean.d2_mse += f.d2_mse;
    mean.accuracy_rms += f.accuracy_rms;
    mean.completeness_rms += f.completeness_rms;
    mean.hausdorff += f.hausdorff;
    mean.coverage += f.coverage;
  }
  const double n = static_cast<double>(frames.size());
  mean.d1_mse_test_to_ref /= n;
  mean.d1_mse_ref_to_test /= n;
  mean.d1_mse /= n;
  mean.d2_mse_test_to_ref /= n;
  mean.d2_mse_ref_to_test /= n;
  mean.d2_mse /= n;
  mean.accuracy_rms /= n;
  mean.completeness_rms /= n;
  mean.hausdorff /= n;
  mean.coverage /= n;
  mean.d1_psnr = PsnrFromMse(mean.d1_mse, peak);
  mean.d2_psnr = PsnrFromMse(mean.d2_mse, peak);
  // Colour: the mean of the per-frame PSNRs (each at most kFramePsnrCapDb), when every frame
  // has colour on both sides.
  mean.has_colour = !frames.empty() && std::all_of(frames.begin(), frames.end(),
                                                   [](const FrameMetrics& f) { return f.has_colour; });
  if (mean.has_colour) {
    for (const FrameMetrics& f : frames) {
      mean.y_psnr += std::min(f.y_psnr, kFramePsnrCapDb) / n;
      mean.cb_psnr += std::min(f.cb_psnr, kFramePsnrCapDb) / n;
      mean.cr_psnr += std::min(f.cr_psnr, kFramePsnrCapDb) / n;
      mean.yuv_psnr += std::min(f.yuv_psnr, kFramePsnrCapDb) / n;
      mean.y_psnr_test_to_ref += std::min(f.y_psnr_test_to_ref, kFramePsnrCapDb) / n;
    }
  }
  return mean;
}

PsnrMeanOfFrames MeanOfFramePsnrs(const std::vector<FrameMetrics>& frames) {
  PsnrMeanOfFrames result;
  if (frames.empty()) {
    result.d1_psnr = result.d2_psnr = std::numeric_limits<double>::quiet_NaN();
    return result;
  }
  for (const FrameMetrics& f : frames) {
    result.d1_psnr += std::min(f.d1_psnr, kFramePsnrCapDb);
    result.d2_psnr += std::min(f.d2_psnr, kFramePsnrCapDb);
    if (f.d1_psnr >= kFramePsnrCapDb) ++result.d1_capped_frames;
    if (f.d2_psnr >= kFramePsnrCapDb) ++result.d2_capped_frames;
  }
  const double n = static_cast<double>(frames.size());
  result.d1_psnr /= n;
  result.d2_psnr /= n;
  return result;
}

StatusOr<EvalResult> EvaluateSequences(MeshSequence& ref, MeshSequence& test,
                                       const EvalOptions& options,
                                       const ProgressCallback& progress) {
  const int ref_first = options.ref_first.value_or(0);
  if (ref_first < 0) {
    return InvalidArgumentError("the reference's first frame " + std::to_string(ref_first) +
                                " is negative");
  }
  // The reference's frames from ref_first on, numbered as the test's.
  const int ref_count = std::max(0, ref.frame_count() - ref_first);
  const int test_count = test.frame_count();
  const std::string ref_frames =
      !options.ref_first ? std::to_string(ref.frame_count()) + " frames"
                     : std::to_string(ref_count) + " frames from its frame " +
                           std::to_string(ref_first) + " on";
  int first = options.first_frame;
  int end = options.end_frame;
  if (end < 0) {
    if (!options.ref_first ? ref_count != test_count : ref_count < test_count) {
      return InvalidArgumentError(
          "frame counts differ: the reference " + ref.description() + " has " + ref_frames +
          ", the test " + test.description() + " has " + std::to_string(test_count) +
          "; choose a common range with --frames A:B, or with --ref-first N when the test "
          "starts at the reference's frame N (encoded with --frames N:...)");
    }
    end = test_count;
  }
  if (first < 0 || first >= end) {
    return InvalidArgumentError("empty frame range " + std::to_string(first) + ":" +
                                std::to_string(end));
  }
  if (end > ref_count || end > test_count) {
    return InvalidArgumentError(
        "frame range " + std::to_string(first) + ":" + std::to_string(end) +
        " is not in both sequences: the reference " + ref.description() + " has " +
        ref_frames + ", the test " + test.description() + " has " +
        std::to_string(test_count));
  }

  EvalResult result;
  result.ref_description = ref.description();
  result.test_description = test.description();
  result.first_frame = first;
  result.end_frame = end;
  result.ref_first = ref_first;
  result.samples = options.samples;
  result.seed = options.seed;
  if (options.peak > 0) {
    result.peak = options.peak;
  } else {
    MESHVID_ASSIGN_OR_RETURN(result.peak, SequenceBoundingBoxDiagonal(ref, progress));
    if (!(result.peak > 0)) {
      return InvalidArgumentError("the reference " + ref.description() +
                                  " has a zero-size bounding box; PSNR needs a positive peak");
    }
  }
  result.coverage_tolerance = options.coverage_tolerance >= 0
                                  ? options.coverage_tolerance
                                  : kDefaultCoverageToleranceRatio * result.peak;

  MetricOptions metric_options;
  metric_options.samples = options.samples;
  metric_options.peak = result.peak;
  metric_options.coverage_tolerance = result.coverage_tolerance;
  const long total = end - first;
  for (int t = first; t < end; ++t) {
    if (!ReportProgress(progress, "evaluate", t - first, total)) {
      return CancelledError("evaluation cancelled");
    }
    const int ref_frame = ref_first + t;
    StatusOr<TriangleMesh> ref_mesh = ref.Frame(ref_frame);
    if (!ref_mesh.ok()) {
      return ref_mesh.status().WithContext("reference " + ref.description() + ", frame " +
                                           std::to_string(ref_frame));
    }
    StatusOr<TriangleMesh> test_mesh = test.Frame(t);
    if (!test_mesh.ok()) {
      return test_mesh.status().WithContext("test " + test.description() + ", frame " +
                                            std::to_string(t));
    }
    metric_options.seed = MixSeed(options.seed, static_cast<std::uint64_t>(ref_frame));
    StatusOr<FrameMetrics> metrics = ComputeFrameMetrics(*ref_mesh, *test_mesh, metric_options);
    if (!metrics.ok()) return metrics.status().WithContext("frame " + std::to_string(t));
    metrics->frame = t;
    result.frames.push_back(*metrics);
  }
  ReportProgress(progress, "evaluate", total, total);
  result.mean = MeanFrameMetrics(result.frames, result.peak);
  result.mean_of_frames = MeanOfFramePsnrs(result.frames);
  return result;
}

}  // namespace meshvid
