// What `meshvid bench` takes from the JSON of `meshvid eval --json` (tools/eval/eval_report.cc:
// "mean" and "frames"), and how it completes points recorded before they held per-frame
// figures from the eval JSON files a run left in its work folder, without measuring again.
#ifndef MESHVID_TOOLS_BENCH_EVAL_FIGURES_H_
#define MESHVID_TOOLS_BENCH_EVAL_FIGURES_H_

#include <limits>
#include <string>
#include <vector>

#include "format/status.h"
#include "tools/bench/bench_record.h"

namespace meshvid {

/// The figures of one `meshvid eval --json` file a bench point records.
struct EvalFigures {
  // "mean": over frames (PSNRs of the mean MSE, and as the mean of the per-frame PSNRs).
  double d1_psnr = std::numeric_limits<double>::quiet_NaN();
  double d2_psnr = std::numeric_limits<double>::quiet_NaN();
  double d1_psnr_mean_of_frames = std::numeric_limits<double>::quiet_NaN();
  double d2_psnr_mean_of_frames = std::numeric_limits<double>::quiet_NaN();
  double accuracy_rms = std::numeric_limits<double>::quiet_NaN();
  double completeness_rms = std::numeric_limits<double>::quiet_NaN();
  double hausdorff = std::numeric_limits<double>::quiet_NaN();
  double coverage = std::numeric_limits<double>::quiet_NaN();
  double y_psnr = std::numeric_limits<double>::quiet_NaN();    ///< NaN: no colour evaluated
  double yuv_psnr = std::numeric_limits<double>::quiet_NaN();  ///< as y_psnr
  int frames = 0;  ///< entries of "frames"
  /// Per frame, in the file's order, rounded by RoundFrameFigure; NaN where a frame has none.
  std::vector<double> frame_accuracy_rms;
  std::vector<double> frame_d1_psnr;
};

/// Parses the text of a `meshvid eval --json` file (`name` in messages). Fails with kCorrupt
/// when it is not a JSON object with a "mean" object.
StatusOr<EvalFigures> ParseEvalFigures(const std::string& text, const std::string& name);

/// Copies every figure of `figures` into `point` (means, colour, frame count, per-frame
/// arrays).
void SetEvalFigures(const EvalFigures& figures, BenchPoint* point);

/// The file name stem of a point's work files in its record's work folder, as the runner
/// names them: "draco-b12" (baseline), "hevc-q40-L2" (meshvid).
std::string PointWorkStem(const BenchPoint& point);

/// Where the runner writes the eval JSON of `point`:
/// <work_dir>/<sequence>-<rig>/<stem>.eval.json.
std::string EvalJsonPath(const std::string& work_dir, const BenchRecord& record,
                         const BenchPoint& point);

/// Gives `point` the per-frame figures of the eval JSON file at `path`, if that file is the
/// evaluation the point recorded: same frame count, same mean D1 PSNR (of the mean MSE) and
/// accuracy RMS. Nothing else of the point changes. Fails with kNotFound when the file is
/// missing, kCorrupt when it does not parse, kInvalidArgument when it is another
/// evaluation's.
Status FillFrameFiguresFromEvalJson(const std::string& path, BenchPoint* point);

/// For every successful point of `record` without per-frame figures (an older record), fills
/// them from its eval JSON in `work_dir` (FillFrameFiguresFromEvalJson) when it is there.
/// Returns how many points were filled.
int BackfillFrameFigures(BenchRecord& record, const std::string& work_dir);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_BENCH_EVAL_FIGURES_H_
