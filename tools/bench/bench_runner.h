// `meshvid bench` as a library: for each ground-truth sequence and rig, simulate a capture,
// encode it with meshvid at several rate points per codec, decode and evaluate every level,
// run the per-frame baseline (fusion + Draco) on the same capture, in full and decimated to
// meshvid's decoded vertex count (and 2x and 1/2 of it), evaluate it the same way, and record
// everything (bench_record.h). Every step runs as a child process of the
// `meshvid` executable, measured for wall time and peak memory; a failing step is recorded
// and the run goes on. Finished steps found in an existing record are not run again: points
// of an older record without the per-frame figures get them from their eval JSON in the work
// folder when it is still there (eval_figures.h); such points whose eval JSON is gone, and
// points without the mean of per-frame PSNRs, are measured again. Every record also holds its
// divergence check (bench_divergence.h).
#ifndef MESHVID_TOOLS_BENCH_BENCH_RUNNER_H_
#define MESHVID_TOOLS_BENCH_BENCH_RUNNER_H_

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "codec/common/progress.h"
#include "format/status.h"
#include "tools/bench/bench_record.h"

namespace meshvid {

/// One ground-truth sequence to benchmark.
struct BenchSequence {
  std::string name;          ///< short name used in file names ("samba", "cloth")
  std::string ground_truth;  ///< what `meshvid simulate` reads (a path or scene:NAME)
  double azimuth_deg = 0;    ///< rig rotation so the arc faces the subject's front
};

/// One simulated rig.
struct BenchRig {
  int views = 3;
  std::string layout = "arc";  ///< "arc" or "ring"
  /// "3-arc".
  std::string name() const { return std::to_string(views) + "-" + layout; }
};

/// Everything a bench run does.
struct BenchOptions {
  std::string meshvid;  ///< path of the `meshvid` executable the steps run
  std::vector<BenchSequence> sequences;
  std::vector<BenchRig> rigs = {{3, "arc"}, {6, "ring"}};
  std::vector<std::string> codecs = {"hevc", "av1"};  ///< lossy codecs, one curve each
  std::vector<int> qualities = {20, 40, 60, 80};      ///< `meshvid encode --quality`
  /// FFV1 as the lossless reference: one point at this quality; < 0: none.
  int lossless_quality = 100;
  std::vector<int> position_bits = {8, 10, 12, 14};  ///< baseline Draco settings
  /// Draco settings of the decimated baseline (each fused frame decimated to 1/2, 1 and 2
  /// times the default meshvid point's decoded vertex count); empty: no decimated baseline.
  std::vector<int> decimated_bits = {8, 10, 12};
  int frames = 0;                                    ///< capture frames per sequence (0: all)
  std::size_t eval_samples = 200000;                 ///< `meshvid eval --samples`
  std::string results_dir = "bench/results";         ///< records <sequence>-<rig>.json
  std::string work_dir = "bench/results/tmp";        ///< captures, .mvid files, logs
  bool resume = true;                                ///< reuse finished steps of existing records
  bool keep_work = false;  ///< keep the baseline's decoded frames after evaluation
  /// Draw each record's still (BenchStillName) with `meshvid render` after its points.
  bool draw_stills = true;
  /// Extra arguments of every `meshvid encode` (e.g. {"--rebase-gain", "4"}): a setting measured
  /// against the baseline as the default encoder is. Part of each record's run key, so a
  /// record made with other extra arguments is started afresh (give such runs their own -o).
  std::vector<std::string> encode_args;
};

/// How a run reports to its caller (the CLI draws and prints these).
struct BenchEvents {
  /// Steps done out of the steps planned (the total grows when a file's levels are known).
  ProgressCallback progress;
  /// One line per finished or failed step, e.g. "samba 3-arc hevc q40 L2: 1.2 kB/frame ...".
  std::function<void(const std::string&)> log;
};

/// Resolves `--sequences`: a comma-separated list of names in `shared_data`/sequences
/// ("samba"), built-in scenes ("cloth" or "scene:cloth") and paths to ground truth (NAME.obj
/// with NAME.pc2, a folder, a {frame} pattern). An empty list means every sequence of the
/// shared data plus both built-in scenes. Fails naming what is available for an unknown name.
StatusOr<std::vector<BenchSequence>> ResolveBenchSequences(const std::string& list,
                                                           const std::string& shared_data);

/// Parses "20,40,60" into numbers in [lo, hi]; `what` names the option in messages.
StatusOr<std::vector<int>> ParseIntList(const std::string& text, int lo, int hi,
                                        const std::string& what);

/// Parses "3-arc,6-ring" (VIEWS-LAYOUT items, layout arc or ring).
StatusOr<std::vector<BenchRig>> ParseRigList(const std::string& text);

/// Splits `--encode-args` at white space into the extra arguments of every `meshvid encode`.
/// Fails naming an argument the bench sets itself (the output, codec, quality, summary,
/// frames, quiet).
StatusOr<std::vector<std::string>> ParseEncodeArgs(const std::string& text);

/// The shared data folder: $MESHVID_SHARED_DATA, else ../shared/data if it exists, else the
/// one beside the source tree the program was built from; "" if none exists.
std::string DefaultSharedDataDir();

/// Runs the benchmark. Returns the records of every sequence and rig (also written to
/// results_dir); fails only when nothing can proceed (folders cannot be created, the
/// executable is missing, progress asked to stop).
StatusOr<std::vector<BenchRecord>> RunBench(const BenchOptions& options,
                                            const BenchEvents& events = {});

/// The UTC time now, ISO 8601 ("2026-11-22T10:04:05Z").
std::string UtcTimestamp();

}  // namespace meshvid

#endif  // MESHVID_TOOLS_BENCH_BENCH_RUNNER_H_
