// Sequence-level evaluation: a test sequence against ground truth, frame by frame, with the
// mean over frames, as a table for the terminal and as JSON. A sequence's PSNR is given both
// ways: of the mean MSE over frames, and as the mean of the per-frame PSNRs (how MPEG's common
// test conditions average a sequence, so figures compare with published ones).
#ifndef MESHVID_TOOLS_EVAL_EVALUATION_H_
#define MESHVID_TOOLS_EVAL_EVALUATION_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "codec/common/progress.h"
#include "format/status.h"
#include "tools/eval/metrics.h"
#include "tools/io/mesh_sequence.h"

namespace meshvid {

/// Default coverage tolerance as a share of the peak p: 0.25% of the ground truth's
/// bounding-box diagonal (about 5 mm for a 2 m subject).
inline constexpr double kDefaultCoverageToleranceRatio = 0.0025;

/// In the mean of per-frame PSNRs, a frame's PSNR counts as at most this many dB (as libvpx
/// caps its per-frame PSNR), so an exact frame (PSNR +inf) cannot make the mean infinite. The
/// frames capped are counted; an exact frame is one of them.
inline constexpr double kFramePsnrCapDb = 100.0;

/// The mean over frames of each frame's PSNR, each capped at kFramePsnrCapDb.
struct PsnrMeanOfFrames {
  double d1_psnr = 0;        ///< dB; NaN when there is no frame
  double d2_psnr = 0;        ///< dB; NaN when there is no frame
  int d1_capped_frames = 0;  ///< frames whose D1 PSNR was >= the cap (exact frames included)
  int d2_capped_frames = 0;  ///< frames whose D2 PSNR was >= the cap
};

/// What to evaluate and how.
struct EvalOptions {
  /// The test's frames [first_frame, end_frame). end_frame < 0 means every frame, and then the
  /// reference must have as many frames from ref_first on as the test has; otherwise both must
  /// hold the range.
  int first_frame = 0;
  int end_frame = -1;
  /// The reference frame the test's frame 0 is measured against (a file encoded with
  /// `meshvid encode --frames N:...` starts at the capture's frame N): test frame t against
  /// reference frame ref_first + t, sampled as a run over the whole reference samples it.
  /// Given (even 0), the reference may run on past the test's last frame; unset, frame 0 and
  /// both must have as many frames.
  std::optional<int> ref_first;
  std::size_t samples = 200000;  ///< area-weighted samples per surface and frame
  std::uint64_t seed = 1;        ///< sampling seed (mixed with the frame number)
  /// Absolute coverage tolerance; < 0 selects kDefaultCoverageToleranceRatio * peak.
  double coverage_tolerance = -1;
  /// PSNR peak; < 0 selects the diagonal of the reference's bounding box over ALL its frames
  /// (not only the evaluated range, so a sub-range's PSNR compares with the full run's).
  double peak = -1;
};

/// The outcome of an evaluation, with the settings that produced it.
struct EvalResult {
  std::string ref_description;
  std::string test_description;
  int first_frame = 0;
  int end_frame = 0;
  int ref_first = 0;  ///< EvalOptions::ref_first
  std::size_t samples = 0;
  std::uint64_t seed = 0;
  double peak = 0;                ///< p used by the PSNRs
  double coverage_tolerance = 0;  ///< absolute tolerance used by coverage
  std::vector<FrameMetrics> frames;
  /// Mean over frames of every field (frame = -1). The PSNRs are those of the mean MSEs,
  /// 10 log10(3 p^2 / mean MSE): finite unless every frame is exact, never a mean of infinities.
  FrameMetrics mean;
  /// The mean of the per-frame PSNRs (MPEG CTC averaging). Never below the PSNR of the mean MSE
  /// unless frames were capped: a few bad frames weigh less here than in `mean`.
  PsnrMeanOfFrames mean_of_frames;
};

/// Diagonal of the bounding box of every frame of `sequence`, reporting progress as "bounds".
StatusOr<double> SequenceBoundingBoxDiagonal(MeshSequence& sequence,
                                             const ProgressCallback& progress = {});

/// The mean of `frames` as described in EvalResult::mean; `peak` is used for the PSNRs.
FrameMetrics MeanFrameMetrics(const std::vector<FrameMetrics>& frames, double peak);

/// The mean of the per-frame PSNRs of `frames`, as described in PsnrMeanOfFrames.
PsnrMeanOfFrames MeanOfFramePsnrs(const std::vector<FrameMetrics>& frames);

/// Evaluates `test` against the ground truth `ref` frame by frame, reporting progress as
/// "evaluate" (one unit per frame). Fails with a clear message if the frame counts disagree
/// over the range, a frame cannot be read, or a frame has no area. A result's frame numbers
/// are the test's.
StatusOr<EvalResult> EvaluateSequences(MeshSequence& ref, MeshSequence& test,
                                       const EvalOptions& options,
                                       const ProgressCallback& progress = {});

/// The result as JSON text: {"settings": {...}, "peak", "coverage_tolerance",
/// "frame_psnr_cap", "frames": [...], "mean": {...}}. "mean" holds EvalResult::mean (its
/// "d1_psnr"/"d2_psnr" are of the mean MSE) and the mean of frames as
/// "d1_psnr_mean_of_frames", "d2_psnr_mean_of_frames", "d1_psnr_capped_frames" and
/// "d2_psnr_capped_frames". An infinite PSNR is written as the string "inf".
std::string EvalResultToJson(const EvalResult& result);

/// Writes EvalResultToJson to `path`; fails naming the file if it cannot be written.
Status WriteEvalJson(const EvalResult& result, const std::string& path);

/// A fixed-width table: one row per frame, then the mean as two rows, "mean MSE" (PSNRs of the
/// mean MSE, other columns their mean over frames) and "mean of frames" (the mean of per-frame
/// PSNRs), and a line explaining both; an infinite PSNR prints as "inf".
std::string FormatEvalTable(const EvalResult& result);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_EVAL_EVALUATION_H_
