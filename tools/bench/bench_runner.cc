#include "tools/bench/bench_runner.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>
#include <nlohmann/json.hpp>

#include "tools/bench/baseline.h"
#include "tools/bench/bench_divergence.h"
#include "tools/bench/bench_report.h"
#include "tools/bench/child_process.h"
#include "tools/bench/eval_figures.h"
#include "tools/json/json_number.h"
#include "tools/io/capture.h"

namespace meshvid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// A figure of the JSON a child process wrote (JsonNumber); NaN if it is not a number.
double ChildFigure(const json& j, const char* key) {
  try {
    return JsonNumber(j, key);
  } catch (const std::invalid_argument&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

StatusOr<json> ReadJsonFile(const std::string& path) {
  MESHVID_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
  json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return CorruptError(path + ": not a JSON object");
  return j;
}

/// A point a resumed run keeps: measured, with the figures this version records (a point of an
/// older record lacks the mean of per-frame PSNRs, the per-frame figures or its colour bytes,
/// so it is measured again, unless the per-frame figures were filled from its eval JSON:
/// BackfillFrameFigures).
bool Finished(const BenchPoint* point) {
  return point != nullptr && point->ok && HasMeanOfFramesPsnr(*point) && HasFrameFigures(*point) &&
         !std::isnan(point->colour_bytes_per_frame);
}

/// Arguments joined by single spaces ("" for none).
std::string JoinArgs(const std::vector<std::string>& args) {
  std::string text;
  for (const std::string& arg : args) text += (text.empty() ? "" : " ") + arg;
  return text;
}

/// The run key's part for the encoder's extra arguments: nothing without them, so the keys of
/// records made before the option existed still match.
std::string EncodeArgsKey(const std::vector<std::string>& args) {
  return args.empty() ? std::string() : ";encode_args=" + JoinArgs(args);
}

std::string JoinInts(const std::vector<int>& values) {
  std::string text;
  for (int v : values) text += (text.empty() ? "" : ",") + std::to_string(v);
  return text;
}

std::string Format(const char* format, double a, double b = 0, double c = 0, double d = 0) {
  char text[256];
  std::snprintf(text, sizeof(text), format, a, b, c, d);
  return text;
}

/// "exit code 1: <last lines of the log> (log: PATH)".
std::string ChildFailure(const StatusOr<ChildRun>& run) {
  if (!run.ok()) return run.status().ToString();
  std::string text = run->signal != 0 ? "killed by signal " + std::to_string(run->signal)
                                      : "exit code " + std::to_string(run->exit_code);
  const std::string tail = LogTail(run->log_path);
  if (!tail.empty()) text += ": " + tail;
  return text + " (log: " + run->log_path + ")";
}

/// The state of one bench run: options, progress counters and the current record.
class Runner {
 public:
  Runner(const BenchOptions& options, const BenchEvents& events)
      : options_(options), events_(events) {}

  StatusOr<std::vector<BenchRecord>> Run() {
    if (FindProgram(options_.meshvid).empty()) {
      return NotFoundError("the meshvid executable '" + options_.meshvid + "' was not found");
    }
    if (options_.sequences.empty() || options_.rigs.empty()) {
      return InvalidArgumentError("nothing to benchmark: no sequence or no rig");
    }
    for (const std::string& folder : {options_.results_dir, options_.work_dir}) {
      std::error_code error;
      fs::create_directories(folder, error);
      if (error) return IoError(folder + ": cannot create: " + error.message());
    }
    const long per_rig = 1 + 1 + static_cast<long>(options_.position_bits.size()) +
                         static_cast<long>(Configurations().size()) * (1 + kAssumedLevels + 1) +
                         DecimatedSteps();
    total_ = per_rig * static_cast<long>(options_.sequences.size() * options_.rigs.size());
    machine_ = ReadMachineInfo();
    std::vector<BenchRecord> records;
    for (const BenchSequence& sequence : options_.sequences) {
      for (const BenchRig& rig : options_.rigs) {
        BenchRecord record;
        const Status status = RunOne(sequence, rig, &record);
        records.push_back(record);
        if (!status.ok()) return status;
      }
    }
    return records;
  }

 private:
  static constexpr int kAssumedLevels = 3;  // for the step count before a file is opened

  /// (codec, quality) of every meshvid encode.
  std::vector<std::pair<std::string, int>> Configurations() const {
    std::vector<std::pair<std::string, int>> configs;
    for (const std::string& codec : options_.codecs) {
      for (int q : options_.qualities) configs.emplace_back(codec, q);
    }
    if (options_.lossless_quality >= 0) configs.emplace_back("ffv1", options_.lossless_quality);
    return configs;
  }

  /// The decimated baseline's steps: its run, then one point per multiple and bits.
  long DecimatedSteps() const {
    if (options_.decimated_bits.empty()) return 0;
    return 1 + static_cast<long>(std::size(kDecimatedMultiples) * options_.decimated_bits.size());
  }

  /// Counts `steps` finished steps; false if the caller asked to stop.
  bool Advance(long steps = 1) {
    done_ += steps;
    total_ = std::max(total_, done_);
    return ReportProgress(events_.progress, "bench", done_, total_);
  }

  void Log(const std::string& line) const {
    if (events_.log) events_.log(line);
  }

  Status Save(BenchRecord& record) {
    ComputeBdRates(record);
    ComputeDivergence(record);
    struct rusage self {};
    if (getrusage(RUSAGE_SELF, &self) == 0)
      record.bench_process_peak_mb = self.ru_maxrss * 1024.0 / 1e6;
    record.date = UtcTimestamp();
    return WriteBenchRecord(record, record_path_);
  }

  /// Draws the default point's worst frame (BenchStillName) with `meshvid render`; a failure
  /// is logged, not fatal.
  void Still(const BenchRecord& record);

  StatusOr<ChildRun> Child(const std::vector<std::string>& args, const std::string& log_name) {
    std::vector<std::string> argv = {options_.meshvid};
    argv.insert(argv.end(), args.begin(), args.end());
    return RunChild(argv, dir_ + "/logs/" + log_name + ".log");
  }

  /// The command line as a reader would type it ("meshvid ..." rather than the full path).
  static std::string Command(const std::vector<std::string>& args) {
    std::vector<std::string> argv = {"meshvid"};
    argv.insert(argv.end(), args.begin(), args.end());
    return ShellQuoteCommand(argv);
  }

  Status RunOne(const BenchSequence& sequence, const BenchRig& rig, BenchRecord* out);
  Status Simulate(const BenchSequence& sequence, const BenchRig& rig, BenchRecord& record);
  Status Baseline(BenchRecord& record);
  /// The per-frame baseline decimated to kDecimatedMultiples of the default meshvid point's
  /// decoded vertex count, at options_.decimated_bits (after the meshvid encodes).
  Status Decimated(BenchRecord& record);
  /// Records the encodes and points of `summary`'s settings (method `method`, codecs[i] for
  /// setting i): Draco decoding timed in a child, every setting evaluated; removes the
  /// decoded frames under `out` once every point is measured (unless keep_work).
  Status DracoPoints(BenchRecord& record, const std::string& method,
                     const std::vector<std::string>& codecs, const BaselineSummary& summary,
                     const std::string& out, const std::string& command, const StepCost& cost);
  Status Meshvid(BenchRecord& record, const std::string& codec, int quality);
  /// Fills `encode`'s levels, frames, bytes and colour bytes from `meshvid info` of its file;
  /// on failure, sets encode->ok false with the reason.
  void ReadFileInfo(const std::string& stem, BenchEncode* encode);
  /// Runs `meshvid eval` of `test` (at `level` if >= 0) into `point`; false if it failed.
  bool Evaluate(const BenchRecord& record, const std::string& test, int level,
                const std::string& stem, BenchPoint* point);

  const BenchOptions& options_;
  const BenchEvents& events_;
  MachineInfo machine_;
  long done_ = 0;
  long total_ = 0;
  std::string dir_;          // work folder of the current sequence and rig
  std::string record_path_;  // its record
  std::string label_;        // "samba 3-arc", for log lines
};

Status Runner::RunOne(const BenchSequence& sequence, const BenchRig& rig, BenchRecord* out) {
  const std::string name = sequence.name + "-" + rig.name();
  dir_ = options_.work_dir + "/" + name;
  record_path_ = options_.results_dir + "/" + name + ".json";
  label_ = sequence.name + " " + rig.name();
  std::error_code error;
  fs::create_directories(dir_ + "/logs", error);
  if (error) return IoError(dir_ + "/logs: cannot create: " + error.message());

  BenchRecord& record = *out;
  const std::string run_key = "gt=" + sequence.ground_truth + ";rig=" + rig.name() +
                              ";frames=" + std::to_string(options_.frames) +
                              ";samples=" + std::to_string(options_.eval_samples) +
                              ";azimuth=" + Format("%g", sequence.azimuth_deg) +
                              EncodeArgsKey(options_.encode_args);
  if (options_.resume && fs::exists(record_path_)) {
    StatusOr<BenchRecord> previous = ReadBenchRecord(record_path_);
    if (previous.ok() && previous->run_key == run_key) {
      record = std::move(*previous);
      // Points recorded before the per-frame figures: from their eval JSON, if still there.
      const int filled = BackfillFrameFigures(record, options_.work_dir);
      if (filled > 0) {
        Log(label_ + ": " + std::to_string(filled) +
            " points got their per-frame figures from their eval JSON in " + dir_);
      }
      long older = 0, no_frames = 0;
      for (const BenchPoint& p : record.points) {
        older += p.ok && !HasMeanOfFramesPsnr(p);
        no_frames += p.ok && HasMeanOfFramesPsnr(p) && !HasFrameFigures(p);
      }
      if (older > 0) {
        Log(label_ + ": " + std::to_string(older) +
            " points were recorded without the mean of per-frame PSNRs; measuring them again");
      }
      if (no_frames > 0) {
        Log(label_ + ": " + std::to_string(no_frames) +
            " points were recorded without per-frame figures and their eval JSON is gone; "
            "measuring them again");
      }
    } else {
      Log(label_ + ": " + record_path_ + " was made with other settings; starting afresh");
    }
  }
  record.sequence = sequence.name;
  record.ground_truth = sequence.ground_truth;
  record.rig = rig.name();
  record.views = rig.views;
  record.layout = rig.layout;
  record.eval_samples = static_cast<int>(options_.eval_samples);
  record.run_key = run_key;
  record.encode_args = JoinArgs(options_.encode_args);
  record.machine = machine_;

  MESHVID_RETURN_IF_ERROR(Simulate(sequence, rig, record));
  if (!record.simulate_ok) {
    // Nothing else can run on this sequence and rig; skip its planned steps.
    const long skipped = static_cast<long>(options_.position_bits.size()) + 1 +
                         static_cast<long>(Configurations().size()) * (kAssumedLevels + 2) +
                         DecimatedSteps();
    if (!Advance(skipped)) return CancelledError("bench cancelled");
    return Status::Ok();
  }
  MESHVID_RETURN_IF_ERROR(Baseline(record));
  for (const auto& [codec, quality] : Configurations()) {
    MESHVID_RETURN_IF_ERROR(Meshvid(record, codec, quality));
  }
  MESHVID_RETURN_IF_ERROR(Decimated(record));
  MESHVID_RETURN_IF_ERROR(Save(record));
  Log(label_ + " " + DescribeDivergence(record.divergence));
  if (options_.draw_stills) Still(record);
  return Status::Ok();
}

void Runner::Still(const BenchRecord& record) {
  const BenchPoint* point = FindDefaultPoint(record);
  if (point == nullptr || !point->ok) return;
  const std::string mvid =
      dir_ + "/" + point->codec + "-q" + std::to_string(point->quality) + ".mvid";
  if (!fs::exists(mvid)) return;
  const DivergenceCheck& d = record.divergence;
  const int frame = d.has_frames && d.worst_frame >= 0 ? d.worst_frame : 0;
  const std::vector<std::string> args = {
      "render", dir_ + "/capture/manifest.json", "--compare", mvid, "--compare",
      record.reference, "--error-against", record.reference, "--level",
      std::to_string(point->level), "--frames", std::to_string(frame) + ":" +
      std::to_string(frame + 1), "--size", "400x300", "-q", "-o",
      options_.results_dir + "/" + BenchStillName(record)};
  const StatusOr<ChildRun> run = Child(args, "still");
  if (!run.ok() || !run->ok()) {
    Log(label_ + ": the still was not drawn (" +
        (run.ok() ? "see " + run->log_path : run.status().message()) + ")");
  }
}

Status Runner::Simulate(const BenchSequence& sequence, const BenchRig& rig, BenchRecord& record) {
  const std::string capture_dir = dir_ + "/capture";
  const std::string manifest = capture_dir + "/manifest.json";
  record.capture = manifest;
  std::vector<std::string> args = {"simulate", sequence.ground_truth,     "-o",       capture_dir,
                                   "--views",  std::to_string(rig.views), "--layout", rig.layout};
  if (options_.frames > 0)
    args.insert(args.end(), {"--frames", "0:" + std::to_string(options_.frames)});
  if (sequence.azimuth_deg != 0)
    args.insert(args.end(), {"--azimuth", Format("%g", sequence.azimuth_deg)});
  args.push_back("-q");
  record.simulate_command = Command(args);

  if (!(options_.resume && record.simulate_ok && fs::exists(manifest))) {
    const StatusOr<ChildRun> run = Child(args, "simulate");
    record.simulate_ok = run.ok() && run->ok();
    record.simulate_error = record.simulate_ok ? "" : ChildFailure(run);
    if (run.ok()) {
      record.simulate_cost = {run->wall_seconds, run->cpu_seconds, run->peak_rss_mb};
    }
  }
  if (record.simulate_ok) {
    StatusOr<std::unique_ptr<CaptureSequence>> capture = CaptureSequence::Open(manifest);
    if (capture.ok()) {
      record.frames = (*capture)->frame_count();
      record.frame_rate = (*capture)->info().frame_rate;
    } else {
      record.simulate_ok = false;
      record.simulate_error = capture.status().ToString();
    }
  }
  record.reference = fs::exists(capture_dir + "/ground_truth.obj")
                         ? capture_dir + "/ground_truth.obj"
                         : capture_dir + "/ground_truth";
  Log(label_ + ": " +
      (record.simulate_ok ? "capture of " + std::to_string(record.frames) + " frames ready"
                          : "simulation FAILED: " + record.simulate_error));
  MESHVID_RETURN_IF_ERROR(Save(record));
  return Advance() ? Status::Ok() : CancelledError("bench cancelled");
}

bool Runner::Evaluate(const BenchRecord& record, const std::string& test, int level,
                      const std::string& stem, BenchPoint* point) {
  const std::string json_path = dir_ + "/" + stem + ".eval.json";
  std::vector<std::string> args = {"eval", "--ref", record.reference, "--test", test};
  if (level >= 0) args.insert(args.end(), {"--level", std::to_string(level)});
  args.insert(args.end(),
              {"--json", json_path, "--samples", std::to_string(options_.eval_samples), "-q"});
  point->commands.push_back(Command(args));
  std::error_code ignored;
  fs::remove(json_path, ignored);
  const StatusOr<ChildRun> run = Child(args, stem + ".eval");
  if (!run.ok() || !run->ok()) {
    point->error = "eval: " + ChildFailure(run);
    return false;
  }
  const StatusOr<std::string> text = ReadTextFile(json_path);
  StatusOr<EvalFigures> figures =
      text.ok() ? ParseEvalFigures(*text, json_path) : StatusOr<EvalFigures>(text.status());
  if (!figures.ok()) {
    point->error = "eval: " + figures.status().ToString();
    return false;
  }
  SetEvalFigures(*figures, point);
  return true;
}

/// "hevc q40 L2: 1.23 kB/frame, 0.25 Mbit/s, D1 68.21 dB (mean of frames; 67.90 of the mean
/// MSE), coverage 97.1%, decode 450 frames/s".
std::string DescribePoint(const BenchPoint& p) {
  std::string text = (p.method == kMethodDecimated ? "decimated " : "") + p.codec + " " +
                     (p.method == kMethodMeshvid ? "q" : "b") + std::to_string(p.quality) +
                     (p.level >= 0 ? " L" + std::to_string(p.level) : std::string());
  if (!p.ok) return text + " FAILED: " + p.error;
  return text +
         Format(": %.2f kB/frame, %.3g Mbit/s, D1 %.2f dB (mean of frames; %.2f of the mean MSE)",
                p.bytes_per_frame / 1e3, p.mbit_per_s, p.d1_psnr_mean_of_frames, p.d1_psnr) +
         Format(", coverage %.1f%%, decode %.0f frames/s", 100 * p.coverage, p.decode_fps) +
         (std::isnan(p.y_psnr) ? std::string()
                               : Format(", colour %.2f kB/frame, Y PSNR %.2f dB",
                                        p.colour_bytes_per_frame / 1e3, p.y_psnr));
}

Status Runner::Baseline(BenchRecord& record) {
  const std::string out = dir_ + "/baseline";
  const std::string summary_path = out + "/summary.json";
  const long steps = 1 + static_cast<long>(options_.position_bits.size());
  bool all_ok = true;
  for (int bits : options_.position_bits) {
    all_ok = all_ok && Finished(FindPoint(record, kMethodBaseline, "draco", bits, -1));
  }
  if (options_.resume && all_ok)
    return Advance(steps) ? Status::Ok() : CancelledError("bench cancelled");

  std::vector<std::string> args = {
      "bench-baseline", record.capture, "-o", out, "--bits", JoinInts(options_.position_bits),
      "--summary-json", summary_path,   "-q"};
  record.baseline_command = Command(args);
  // Reuse a finished baseline run whose decoded frames are still there.
  StatusOr<BaselineSummary> summary = InternalError("not run");
  if (options_.resume && record.baseline_ok) {
    StatusOr<std::string> text = ReadTextFile(summary_path);
    if (text.ok()) summary = ParseBaselineSummary(*text, summary_path);
    if (summary.ok()) {
      for (int bits : options_.position_bits) {
        if (!fs::exists(out + "/b" + std::to_string(bits) + "/f0000.ply"))
          summary = InternalError("gone");
      }
    }
  }
  if (!summary.ok()) {
    Log(label_ + ": baseline (fusion + Draco per frame) running");
    std::error_code ignored;
    fs::remove(summary_path, ignored);
    const StatusOr<ChildRun> run = Child(args, "baseline");
    record.baseline_ok = run.ok() && run->ok();
    record.baseline_error = record.baseline_ok ? "" : ChildFailure(run);
    if (run.ok()) record.baseline_cost = {run->wall_seconds, run->cpu_seconds, run->peak_rss_mb};
    if (record.baseline_ok) {
      StatusOr<std::string> text = ReadTextFile(summary_path);
      summary = text.ok() ? ParseBaselineSummary(*text, summary_path)
                          : StatusOr<BaselineSummary>(text.status());
      if (!summary.ok()) {
        record.baseline_ok = false;
        record.baseline_error = summary.status().ToString();
      }
    }
  }
  MESHVID_RETURN_IF_ERROR(Save(record));
  if (!Advance()) return CancelledError("bench cancelled");
  if (!record.baseline_ok) {
    Log(label_ + ": baseline FAILED: " + record.baseline_error);
    for (int bits : options_.position_bits) {
      BenchPoint point;
      point.method = kMethodBaseline;
      point.codec = "draco";
      point.quality = bits;
      point.error = "baseline: " + record.baseline_error;
      point.commands = {record.baseline_command};
      UpsertPoint(record, point);
    }
    MESHVID_RETURN_IF_ERROR(Save(record));
    return Advance(steps - 1) ? Status::Ok() : CancelledError("bench cancelled");
  }
  record.baseline_fuse_seconds = summary->load_seconds + summary->fuse_seconds;
  std::vector<std::string> codecs(summary->settings.size(), "draco");
  return DracoPoints(record, kMethodBaseline, codecs, *summary, out, record.baseline_command,
                     record.baseline_cost);
}

Status Runner::DracoPoints(BenchRecord& record, const std::string& method,
                           const std::vector<std::string>& codecs, const BaselineSummary& summary,
                           const std::string& out, const std::string& command,
                           const StepCost& cost) {
  bool evaluated_all = true;
  for (std::size_t i = 0; i < summary.settings.size(); ++i) {
    const BaselineSetting& s = summary.settings[i];
    const std::string& codec = codecs[i];
    const std::string folder =
        out + "/" + BaselineSettingFolder(s.target_vertices, s.position_bits);
    const int frames = std::max(1, summary.frames);
    BenchEncode encode;
    encode.method = method;
    encode.codec = codec;
    encode.quality = s.position_bits;
    encode.ok = true;
    encode.file = s.pattern;
    encode.frames = summary.frames;
    encode.bytes_total = static_cast<double>(s.bytes_total);
    encode.colour_bytes_total = static_cast<double>(s.colour_bytes_total);
    // Every setting's frames were fused (and decimated) once for all of them: each counts the
    // whole, as a player's encoder running that setting alone would spend it, and the colouring
    // of its own mesh.
    encode.seconds = summary.load_seconds + summary.fuse_seconds + summary.decimate_seconds +
                     s.colour_seconds + s.encode_seconds;
    encode.encode_fps = encode.seconds > 0 ? frames / encode.seconds : 0;
    encode.decode_fps = s.decode_seconds > 0 ? frames / s.decode_seconds : 0;
    encode.peak_rss_mb = cost.peak_rss_mb;
    encode.target_vertices = static_cast<double>(s.target_vertices);
    encode.command = command;
    UpsertEncode(record, encode);

    BenchPoint* previous = FindPoint(record, method, codec, s.position_bits, -1);
    if (options_.resume && Finished(previous)) {
      if (!Advance()) return CancelledError("bench cancelled");
      continue;
    }
    BenchPoint point;
    point.method = method;
    point.codec = codec;
    point.quality = s.position_bits;
    point.level = -1;
    point.frames = summary.frames;
    point.bytes_per_frame = encode.bytes_total / frames;
    point.colour_bytes_per_frame = encode.colour_bytes_total / frames;
    point.mbit_per_s = point.bytes_per_frame * 8 * record.frame_rate / 1e6;
    point.encode_fps = encode.encode_fps;
    point.encode_peak_mb = cost.peak_rss_mb;
    point.vertices = s.vertices;
    point.commands = {command};
    // The player's side in a process of its own: Draco decoding of every frame's bitstream.
    const std::string stem = "draco-" + (method == kMethodBaseline ? std::string() : method + "-") +
                             BaselineSettingFolder(s.target_vertices, s.position_bits);
    const std::string decode_json = dir_ + "/logs/" + stem + ".decode.json";
    const std::vector<std::string> decode_args = {"bench-draco-decode", folder, "--json",
                                                  decode_json, "-q"};
    point.commands.push_back(Command(decode_args));
    const StatusOr<ChildRun> decode = Child(decode_args, stem + ".decode");
    StatusOr<json> timing = decode.ok() && decode->ok()
                                ? ReadJsonFile(decode_json)
                                : StatusOr<json>(InternalError(ChildFailure(decode)));
    if (timing.ok()) {
      point.decode_fps = ChildFigure(*timing, "frames_per_second");
      point.decode_peak_mb = decode->peak_rss_mb;
      point.ok = Evaluate(record, s.pattern, -1, stem, &point);
    } else {
      point.error = "Draco decoding: " + timing.status().message();
    }
    evaluated_all = evaluated_all && point.ok;
    UpsertPoint(record, point);
    Log(label_ + " " + DescribePoint(point));
    MESHVID_RETURN_IF_ERROR(Save(record));
    if (!Advance()) return CancelledError("bench cancelled");
  }
  if (evaluated_all && !options_.keep_work) {
    // The decoded frames are large (every frame at every setting); the record keeps the numbers.
    for (const BaselineSetting& s : summary.settings) {
      std::error_code ignored;
      fs::remove_all(out + "/" + BaselineSettingFolder(s.target_vertices, s.position_bits),
                     ignored);
    }
  }
  return Status::Ok();
}

Status Runner::Decimated(BenchRecord& record) {
  const long steps = DecimatedSteps();
  if (steps == 0) return Status::Ok();
  const BenchPoint* reference = FindDefaultPoint(record);
  if (reference == nullptr || !reference->ok || !(reference->vertices >= 4)) {
    Log(label_ +
        ": no decimated baseline (the default meshvid point, whose decoded vertex "
        "count it is sized by, was not measured)");
    return Advance(steps) ? Status::Ok() : CancelledError("bench cancelled");
  }
  // The vertex count of each multiple, and the codec name its points are recorded under.
  std::vector<int> targets;
  std::map<std::size_t, std::string> codec_of_target;
  bool all_done = true;
  for (double multiple : kDecimatedMultiples) {
    const int target = static_cast<int>(std::lround(multiple * reference->vertices));
    const std::string codec = DecimatedCodecName(multiple);
    targets.push_back(target);
    codec_of_target[static_cast<std::size_t>(target)] = codec;
    for (int bits : options_.decimated_bits) {
      const BenchEncode* e = FindEncode(record, kMethodDecimated, codec, bits);
      all_done = all_done && Finished(FindPoint(record, kMethodDecimated, codec, bits, -1)) &&
                 e != nullptr && e->target_vertices == target;
    }
  }
  if (options_.resume && all_done) {
    return Advance(steps) ? Status::Ok() : CancelledError("bench cancelled");
  }
  // The targets follow meshvid's file: points of other targets are measured again.
  std::erase_if(record.points, [](const BenchPoint& p) { return p.method == kMethodDecimated; });
  std::erase_if(record.encodes, [](const BenchEncode& e) { return e.method == kMethodDecimated; });

  const std::string out = dir_ + "/decimated";
  const std::string summary_path = out + "/summary.json";
  const std::string target_list = JoinInts(targets);
  const std::vector<std::string> args = {
      "bench-baseline", record.capture, "-o",     out,
      "--decimate",     target_list,    "--bits", JoinInts(options_.decimated_bits),
      "--summary-json", summary_path,   "-q"};
  const std::string command = Command(args);
  Log(label_ + ": decimated baseline (fusion, decimation to " + target_list +
      " vertices, Draco per frame) running");
  std::error_code ignored;
  fs::remove(summary_path, ignored);
  const StatusOr<ChildRun> run = Child(args, "decimated");
  StatusOr<BaselineSummary> summary = InternalError(ChildFailure(run));
  if (run.ok() && run->ok()) {
    StatusOr<std::string> text = ReadTextFile(summary_path);
    summary = text.ok() ? ParseBaselineSummary(*text, summary_path)
                        : StatusOr<BaselineSummary>(text.status());
  }
  if (!Advance()) return CancelledError("bench cancelled");
  if (!summary.ok()) {
    Log(label_ + ": decimated baseline FAILED: " + summary.status().message());
    for (double multiple : kDecimatedMultiples) {
      for (int bits : options_.decimated_bits) {
        BenchPoint point;
        point.method = kMethodDecimated;
        point.codec = DecimatedCodecName(multiple);
        point.quality = bits;
        point.error = "decimated baseline: " + summary.status().message();
        point.commands = {command};
        UpsertPoint(record, point);
      }
    }
    MESHVID_RETURN_IF_ERROR(Save(record));
    return Advance(steps - 1) ? Status::Ok() : CancelledError("bench cancelled");
  }
  std::vector<std::string> codecs;
  for (const BaselineSetting& s : summary->settings)
    codecs.push_back(codec_of_target[s.target_vertices]);
  const StepCost cost{run->wall_seconds, run->cpu_seconds, run->peak_rss_mb};
  return DracoPoints(record, kMethodDecimated, codecs, *summary, out, command, cost);
}

void Runner::ReadFileInfo(const std::string& stem, BenchEncode* encode) {
  // The file's own description: levels, frames and size on disk.
  const StatusOr<ChildRun> info = Child({"info", encode->file, "--json", "-"}, stem + ".info");
  StatusOr<json> j = info.ok() && info->ok() ? ReadJsonFile(info->log_path)
                                             : StatusOr<json>(InternalError(ChildFailure(info)));
  if (j.ok() && j->contains("levels") && j->contains("frames") && j->contains("bytes")) {
    encode->levels = j->at("levels").get<int>();
    encode->frames = j->at("frames").get<int>();
    encode->bytes_total = ChildFigure(j->at("bytes"), "file");
    // A file without colour has no "colour" count: none of its bytes are colour.
    encode->colour_bytes_total =
        j->at("bytes").contains("colour") ? ChildFigure(j->at("bytes"), "colour") : 0.0;
    encode->encode_fps = encode->seconds > 0 ? encode->frames / encode->seconds : 0;
  } else {
    encode->ok = false;
    encode->error = "info: " + (j.ok() ? std::string("unexpected JSON") : j.status().message());
  }
}

Status Runner::Meshvid(BenchRecord& record, const std::string& codec, int quality) {
  const std::string stem = codec + "-q" + std::to_string(quality);
  const std::string file = dir_ + "/" + stem + ".mvid";
  BenchEncode* previous = FindEncode(record, kMethodMeshvid, codec, quality);
  BenchEncode encode;
  if (options_.resume && previous != nullptr && previous->ok && fs::exists(file)) {
    encode = *previous;
    if (std::isnan(encode.colour_bytes_total)) {
      // Recorded before colour was counted: the file's description again, not the encode.
      ReadFileInfo(stem, &encode);
      UpsertEncode(record, encode);
      MESHVID_RETURN_IF_ERROR(Save(record));
    }
  } else {
    encode.method = kMethodMeshvid;
    encode.codec = codec;
    encode.quality = quality;
    encode.file = file;
    std::vector<std::string> args = {"encode",         record.capture,
                                     "-o",             file,
                                     "--codec",        codec,
                                     "--quality",      std::to_string(quality),
                                     "--summary-json", dir_ + "/" + stem + ".summary.json"};
    args.insert(args.end(), options_.encode_args.begin(), options_.encode_args.end());
    args.push_back("-q");
    encode.command = Command(args);
    // A new file: what was measured on the old one (a resumed run whose .mvid is gone, say)
    // is measured again.
    ErasePoints(record, kMethodMeshvid, codec, quality);
    std::error_code ignored;
    fs::remove(file, ignored);
    const StatusOr<ChildRun> run = Child(args, stem + ".encode");
    encode.ok = run.ok() && run->ok();
    if (run.ok()) {
      encode.seconds = run->wall_seconds;
      encode.peak_rss_mb = run->peak_rss_mb;
    }
    if (!encode.ok) encode.error = "encode: " + ChildFailure(run);
    if (encode.ok) ReadFileInfo(stem, &encode);
    UpsertEncode(record, encode);
    MESHVID_RETURN_IF_ERROR(Save(record));
  }
  if (!encode.ok) {
    Log(label_ + " " + stem + " FAILED: " + encode.error);
    return Advance(1 + kAssumedLevels + 1) ? Status::Ok() : CancelledError("bench cancelled");
  }
  total_ += encode.levels - kAssumedLevels;
  if (!Advance()) return CancelledError("bench cancelled");

  for (int level = 0; level <= encode.levels; ++level) {
    BenchPoint* done = FindPoint(record, kMethodMeshvid, codec, quality, level);
    if (options_.resume && Finished(done)) {
      if (!Advance()) return CancelledError("bench cancelled");
      continue;
    }
    const std::string level_stem = stem + "-L" + std::to_string(level);
    BenchPoint point;
    point.method = kMethodMeshvid;
    point.codec = codec;
    point.quality = quality;
    point.level = level;
    point.frames = encode.frames;
    const int frames = std::max(1, encode.frames);
    point.bytes_per_frame = encode.bytes_total / frames;
    point.colour_bytes_per_frame = encode.colour_bytes_total / frames;
    point.mbit_per_s = point.bytes_per_frame * 8 * record.frame_rate / 1e6;
    point.encode_fps = encode.encode_fps;
    point.encode_peak_mb = encode.peak_rss_mb;
    point.commands = {encode.command};

    const std::string decode_json = dir_ + "/logs/" + level_stem + ".decode.json";
    const std::vector<std::string> args = {
        "decode",     file,     "--level",   std::to_string(level),
        "--no-write", "--json", decode_json, "-q"};
    point.commands.push_back(Command(args));
    const StatusOr<ChildRun> run = Child(args, level_stem + ".decode");
    if (run.ok() && run->ok()) {
      point.decode_peak_mb = run->peak_rss_mb;
      StatusOr<json> timing = ReadJsonFile(decode_json);
      const double fps = timing.ok() ? ChildFigure(*timing, "frames_per_second") : NAN;
      // Without the decoder's own timing, the process's wall time (start-up included).
      point.decode_fps = std::isfinite(fps) ? fps : encode.frames / run->wall_seconds;
      if (timing.ok()) point.vertices = ChildFigure(*timing, "vertices");
      point.ok = Evaluate(record, file, level, level_stem, &point);
    } else {
      point.error = "decode: " + ChildFailure(run);
    }
    UpsertPoint(record, point);
    Log(label_ + " " + DescribePoint(point));
    MESHVID_RETURN_IF_ERROR(Save(record));
    if (!Advance()) return CancelledError("bench cancelled");
  }
  return Status::Ok();
}

}  // namespace

StatusOr<std::vector<BenchRecord>> RunBench(const BenchOptions& options,
                                            const BenchEvents& events) {
  Runner runner(options, events);
  return runner.Run();
}

}  // namespace meshvid
