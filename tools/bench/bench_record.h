// The results of `meshvid bench` for one sequence and one rig: every coded file, every
// rate-distortion point (a coded file decoded at one level and evaluated) and the BD-rates
// against the per-frame baseline. Stored as bench/results/<sequence>-<rig>.json, rewritten
// after every finished step so an interrupted or failing run loses nothing it finished.
#ifndef MESHVID_TOOLS_BENCH_BENCH_RECORD_H_
#define MESHVID_TOOLS_BENCH_BENCH_RECORD_H_

#include <limits>
#include <string>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// The value of the "format" key of a record file; other JSON files in the folder (the
/// Google-Benchmark results) are not records.
inline constexpr const char* kBenchRecordFormat = "meshvid-bench-record/1";

/// Method names in records.
inline constexpr const char* kMethodMeshvid = "meshvid";
inline constexpr const char* kMethodBaseline = "baseline";
/// The per-frame baseline decimated to a multiple of meshvid's decoded vertex count; its
/// codec names the multiple ("draco 1x", "draco 2x", "draco 0.5x": DecimatedCodecName).
inline constexpr const char* kMethodDecimated = "decimated";
/// The multiples of meshvid's decoded vertex count the decimated baseline is run at.
inline constexpr double kDecimatedMultiples[] = {0.5, 1.0, 2.0};

/// "draco 1x" for the decimated baseline at `multiple` of meshvid's vertex count.
std::string DecimatedCodecName(double multiple);

/// Which D1 PSNR a BD-rate or RD plot uses (BdRateEntry::psnr): the mean of the per-frame
/// PSNRs (MPEG CTC averaging, the default), or the PSNR of the mean MSE over frames (the only
/// figure of records written before the mean of frames was recorded).
inline constexpr const char* kPsnrMeanOfFrames = "d1_psnr_mean_of_frames";
inline constexpr const char* kPsnrOfMeanMse = "d1_psnr";

/// The divergence check (DivergenceCheck): a frame is within when meshvid's accuracy RMS is at
/// most this many times the baseline's on the same frame...
inline constexpr double kDivergenceRatioLimit = 1.25;
/// ...and the goal is that at least this share of the frames is within.
inline constexpr double kDivergenceShareGoal = 0.95;

/// Colour goals (issue 44): the default point's Y PSNR at most this many dB below the
/// baseline best's, with at most kColourBytesRatioGoal times its colour bytes, and colour at
/// most kColourShareGoal of meshvid's bytes.
inline constexpr double kColourPsnrGapGoal = 1.0;
inline constexpr double kColourBytesRatioGoal = 0.2;  ///< see kColourPsnrGapGoal
inline constexpr double kColourShareGoal = 0.4;       ///< see kColourPsnrGapGoal

/// What one child process step cost.
struct StepCost {
  double wall_seconds = 0;
  double cpu_seconds = 0;
  double peak_rss_mb = 0;  ///< peak resident memory, MB (10^6 bytes)
};

/// One coded representation: a .mvid (method "meshvid") or one Draco setting of the
/// baseline (method "baseline", codec "draco", quality = position bits; method "decimated",
/// codec DecimatedCodecName, quality = position bits).
struct BenchEncode {
  std::string method;
  std::string codec;  ///< "hevc", "av1", "ffv1" or "draco"
  int quality = 0;    ///< meshvid --quality 0..100; baseline: Draco position bits
  bool ok = false;
  std::string error;  ///< why it failed (when !ok)
  std::string file;   ///< the .mvid, or the baseline's decoded frames ({frame} pattern)
  int frames = 0;
  int levels = 0;  ///< finest level stored (baseline: 0)
  double bytes_total = 0;
  /// What colour takes of bytes_total: the .mvid's colour stream, the baseline's colour
  /// attributes; 0 without colour, NaN in records from before it was measured.
  double colour_bytes_total = 0;
  double seconds = 0;     ///< encode wall time (baseline: load, fusion, colour, Draco coding)
  double encode_fps = 0;  ///< frames / seconds
  double peak_rss_mb = 0;
  double decode_fps = 0;  ///< baseline only: Draco decoding, frames / second
  /// Decimated baseline only: the vertex count each fused frame was decimated to.
  double target_vertices = 0;
  std::string command;
};

/// One rate-distortion point: an encode decoded at one level (baseline: level -1) and
/// evaluated against the ground truth.
struct BenchPoint {
  std::string method;
  std::string codec;
  int quality = 0;
  int level = -1;
  bool ok = false;
  std::string error;
  int frames = 0;
  double bytes_per_frame = 0;
  double mbit_per_s = 0;  ///< at the capture's frame rate
  double d1_psnr = 0;     ///< dB, of the mean MSE over frames (meshvid eval's mean.d1_psnr)
  double d2_psnr = 0;     ///< dB, of the mean MSE over frames
  /// dB, the mean of the per-frame PSNRs, each at most 100 dB (meshvid eval's
  /// mean.d1_psnr_mean_of_frames); NaN in points recorded before it was (older records).
  double d1_psnr_mean_of_frames = std::numeric_limits<double>::quiet_NaN();
  double d2_psnr_mean_of_frames = std::numeric_limits<double>::quiet_NaN();  ///< as D1
  double accuracy_rms = 0;
  double completeness_rms = 0;
  double hausdorff = 0;
  double coverage = 0;  ///< share of ground-truth samples within tolerance, 0..1
  /// Colour (meshvid eval's mean.y_psnr and mean.yuv_psnr, dB; NaN where the decoded frames
  /// or the ground truth have no colour) and what colour takes of bytes_per_frame (0 without
  /// colour); all NaN in records from before colour was measured.
  double y_psnr = std::numeric_limits<double>::quiet_NaN();
  double yuv_psnr = std::numeric_limits<double>::quiet_NaN();
  double colour_bytes_per_frame = std::numeric_limits<double>::quiet_NaN();
  double encode_fps = 0;
  double decode_fps = 0;
  double encode_peak_mb = 0;
  double decode_peak_mb = 0;
  double vertices = 0;  ///< vertices per decoded frame (mean)
  /// Per-frame figures from the point's `meshvid eval --json` (its "frames"), in frame order,
  /// rounded to 6 significant digits: accuracy RMS and D1 PSNR (dB, not capped; +inf for an
  /// exact frame); NaN where the eval has none. Empty in points recorded before they were.
  std::vector<double> frame_accuracy_rms;
  std::vector<double> frame_d1_psnr;  ///< as frame_accuracy_rms
  std::vector<std::string> commands;  ///< exact commands that produced the point
};

/// The BD-rate of one meshvid curve (a codec decoded at one level, over its qualities)
/// against a reference curve: the full-resolution baseline or one decimated baseline.
struct BdRateEntry {
  /// The reference curve: kMethodBaseline (also what a stored entry without this field was
  /// computed against), or "decimated " + its codec ("decimated draco 1x").
  std::string reference = kMethodBaseline;
  std::string codec;
  int level = 0;
  bool ok = false;
  /// The D1 PSNR it was computed on: kPsnrMeanOfFrames, or kPsnrOfMeanMse for an older record
  /// (also what a stored entry without this field was computed on).
  std::string psnr = kPsnrMeanOfFrames;
  double delta = 0;  ///< fraction: -0.9 = 90% fewer bytes at equal D1 PSNR
  double psnr_low = 0;
  double psnr_high = 0;
  std::string note;  ///< why there is no value (too few points, no overlap)
};

/// meshvid at the encoder's default settings (the default codec and quality, decoded at the
/// finest level its file stores) against the baseline's best setting (the Draco point with
/// the highest D1 PSNR), frame by frame; computed by ComputeDivergence (bench_divergence.h).
struct DivergenceCheck {
  bool has_default = false;   ///< the default point was measured (ok)
  bool has_baseline = false;  ///< a baseline point was measured (ok)
  /// Both points hold per-frame accuracies, so the frame figures below are set.
  bool has_frames = false;
  std::string note;   ///< what is missing or odd, when something is
  std::string codec;  ///< the default point: codec, quality, level
  int quality = 0;
  int level = -1;
  int baseline_bits = 0;  ///< the baseline's best setting: Draco position bits
  /// The D1 PSNR the baseline's best is picked by and compared on (RecordPsnrKind's).
  std::string psnr = kPsnrMeanOfFrames;
  double ratio_limit = kDivergenceRatioLimit;
  int frames = 0;         ///< frames compared
  int frames_within = 0;  ///< frames whose accuracy ratio is <= ratio_limit
  double share_within = std::numeric_limits<double>::quiet_NaN();  ///< frames_within / frames
  /// The frame with the highest ratio (a frame without a figure counts as the highest).
  int worst_frame = -1;
  double worst_meshvid_accuracy_rms = std::numeric_limits<double>::quiet_NaN();
  double worst_baseline_accuracy_rms = std::numeric_limits<double>::quiet_NaN();
  double worst_ratio = std::numeric_limits<double>::quiet_NaN();
  double meshvid_d1_psnr = std::numeric_limits<double>::quiet_NaN();   ///< dB, of `psnr` kind
  double baseline_d1_psnr = std::numeric_limits<double>::quiet_NaN();  ///< dB, of `psnr` kind
  bool share_met = false;  ///< share_within >= kDivergenceShareGoal
  bool psnr_met = false;   ///< meshvid_d1_psnr >= baseline_d1_psnr
};

/// The machine a record was measured on.
struct MachineInfo {
  std::string cpu_model;
  int cores = 0;
  double ram_gb = 0;
  std::string kernel;
};

/// Everything measured for one sequence and rig.
struct BenchRecord {
  std::string sequence;      ///< short name, e.g. "samba", "arm-block"
  std::string ground_truth;  ///< what was simulated (path or scene:NAME)
  std::string rig;           ///< e.g. "3-arc"
  int views = 0;
  std::string layout;  ///< "arc" or "ring"
  int frames = 0;      ///< capture frames
  double frame_rate = 25;
  int eval_samples = 0;   ///< samples per surface used by every evaluation
  std::string capture;    ///< the capture's manifest
  std::string reference;  ///< the ground truth every point is evaluated against
  std::string date;       ///< UTC time of the last update, ISO 8601
  /// The settings a resumed run must share to reuse this record's steps (frames, samples,
  /// ground truth, rig, the encoder's extra arguments).
  std::string run_key;
  /// Extra arguments every meshvid encode of this record was given (BenchOptions::encode_args,
  /// joined by spaces; "" for the encoder's defaults).
  std::string encode_args;
  MachineInfo machine;
  bool simulate_ok = false;
  std::string simulate_error;
  std::string simulate_command;
  StepCost simulate_cost;
  bool baseline_ok = false;  ///< the baseline child (fusion + Draco) finished
  std::string baseline_error;
  std::string baseline_command;
  StepCost baseline_cost;
  double baseline_fuse_seconds = 0;  ///< load + fusion of every frame (shared by all settings)
  /// Peak resident memory of the bench process itself, MB: Linux counts it in every child's
  /// peak (exec keeps the larger high-water mark), so no child reports less.
  double bench_process_peak_mb = 0;
  std::vector<BenchEncode> encodes;
  std::vector<BenchPoint> points;
  std::vector<BdRateEntry> bd_rates;
  DivergenceCheck divergence;  ///< absent in records written before it was (then unset)
};

/// The record's file stem: "<sequence>-<rig>".
std::string BenchRecordName(const BenchRecord& record);

/// The record as JSON text (PSNRs of +-inf as "inf"/"-inf", NaN as null).
std::string BenchRecordToJson(const BenchRecord& record);

/// Parses BenchRecordToJson's output; `name` is used in messages. Fails with kCorrupt on
/// malformed JSON and kUnsupported on JSON that is not a record (another "format").
StatusOr<BenchRecord> ParseBenchRecord(const std::string& text, const std::string& name);

/// Reads and parses a record file.
StatusOr<BenchRecord> ReadBenchRecord(const std::string& path);

/// Writes a record file atomically (a temporary file renamed over `path`), so a crash never
/// leaves a half-written record.
Status WriteBenchRecord(const BenchRecord& record, const std::string& path);

/// Every record in `folder` (*.json whose "format" is kBenchRecordFormat), sorted by name;
/// files that are not records are skipped, a record that fails to parse is an error.
StatusOr<std::vector<BenchRecord>> ReadBenchRecords(const std::string& folder);

/// The encode of (method, codec, quality), or nullptr.
BenchEncode* FindEncode(BenchRecord& record, const std::string& method, const std::string& codec,
                        int quality);
/// The point of (method, codec, quality, level), or nullptr.
BenchPoint* FindPoint(BenchRecord& record, const std::string& method, const std::string& codec,
                      int quality, int level);
/// Stores `point`, replacing the one with the same method, codec, quality and level.
void UpsertPoint(BenchRecord& record, const BenchPoint& point);
/// Stores `encode`, replacing the one with the same method, codec and quality.
void UpsertEncode(BenchRecord& record, const BenchEncode& encode);
/// Removes the points (every level) of (method, codec, quality): they measured a file that is
/// being made again.
void ErasePoints(BenchRecord& record, const std::string& method, const std::string& codec,
                 int quality);

/// True when the point holds the mean of its per-frame PSNRs (points recorded before it was
/// do not).
bool HasMeanOfFramesPsnr(const BenchPoint& point);

/// True when the point holds its per-frame figures, one per frame of the point (points
/// recorded before they were do not).
bool HasFrameFigures(const BenchPoint& point);

/// `value` rounded to 6 significant digits, as per-frame figures are recorded (+-inf and
/// NaN unchanged).
double RoundFrameFigure(double value);

/// The D1 PSNR a record's BD-rates and RD plot use: kPsnrMeanOfFrames when every successful
/// point has it, else kPsnrOfMeanMse (an older record; one figure for all points, so curves
/// stay comparable).
std::string RecordPsnrKind(const BenchRecord& record);

/// The point's D1 PSNR of `kind` (kPsnrMeanOfFrames or kPsnrOfMeanMse).
double D1Psnr(const BenchPoint& point, const std::string& kind);

/// Recomputes record.bd_rates: for every meshvid codec with >= 2 qualities and every level,
/// the BD-rate (RecordPsnrKind's D1 PSNR, bytes per frame, piecewise-cubic) against the
/// baseline's points, then against each decimated baseline's (one curve per multiple).
void ComputeBdRates(BenchRecord& record);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_BENCH_BENCH_RECORD_H_
