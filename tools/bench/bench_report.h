// What `meshvid bench` writes for readers: bench/RESULTS.md (tables, goal check, the exact
// commands, machine, date) and one rate-distortion plot per sequence and rig, drawn by
// gnuplot from a script saved beside it.
#ifndef MESHVID_TOOLS_BENCH_BENCH_REPORT_H_
#define MESHVID_TOOLS_BENCH_BENCH_REPORT_H_

#include <map>
#include <string>
#include <vector>

#include "format/status.h"
#include "tools/bench/bench_record.h"

namespace meshvid {

/// The machine this process runs on: CPU model (/proc/cpuinfo), logical cores, RAM
/// (/proc/meminfo), kernel (uname). Fields it cannot read stay empty or 0.
MachineInfo ReadMachineInfo();

/// What the report says beyond the records.
struct ReportOptions {
  std::string date;          ///< when the report was generated (UTC, ISO 8601)
  std::string command_line;  ///< the bench command as typed
  /// Record name ("samba-3-arc") -> its plot, as a path relative to the report's folder.
  std::map<std::string, std::string> plots;
  /// Said where a plot would be when plots were skipped (e.g. gnuplot is missing).
  std::string plot_note;
  /// Record name -> its still (BenchStillName), relative to the report's folder, if drawn.
  std::map<std::string, std::string> stills;
};

/// The file name of a record's still: the default point's worst frame drawn by `meshvid
/// render` (input views | decoded | ground truth, coloured by distance to the ground truth).
std::string BenchStillName(const BenchRecord& record);

/// The whole RESULTS.md text for `records` (in the order given): the goal check, the
/// "Divergence" table (each record's check computed from its points, bench_divergence.h), then
/// a section per record. Deterministic: the same records and options give the same text.
std::string GenerateResultsMarkdown(const std::vector<BenchRecord>& records,
                                    const ReportOptions& options);

/// A gnuplot script drawing the record's D1 PSNR (RecordPsnrKind's, which its BD-rates use;
/// the y label names it) against Mbit/s (log scale): the baseline, every meshvid codec at every
/// level (the finest level solid), the lossless point. The data are inline; the script writes
/// `png_name` in the folder it is run from. Returns "" if the record has no successful point
/// to draw.
std::string RdPlotScript(const BenchRecord& record, const std::string& png_name);

/// Writes <results_dir>/<name>.gp for every record and runs gnuplot on it (from PATH) to make
/// <results_dir>/<name>-rd.png. Returns record name -> PNG file name. Fails with kNotFound,
/// saying so, if gnuplot is not installed (then nothing is written), and with the log's
/// last lines if gnuplot fails. `log_dir` receives gnuplot's output.
StatusOr<std::map<std::string, std::string>> RenderRdPlots(const std::vector<BenchRecord>& records,
                                                           const std::string& results_dir,
                                                           const std::string& log_dir);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_BENCH_BENCH_REPORT_H_
