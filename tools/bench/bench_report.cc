#include "tools/bench/bench_report.h"

#include <sys/utsname.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <set>
#include <thread>

#include "tools/bench/bench_divergence.h"

namespace meshvid {
namespace {

std::string Fmt(const char* format, double value) {
  if (std::isnan(value)) return "n/a";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string Percent(double fraction) { return Fmt("%+.1f%%", 100 * fraction); }

/// How a D1 PSNR kind (BdRateEntry::psnr) is named in the report.
std::string PsnrKindLabel(const std::string& kind) {
  return kind == kPsnrOfMeanMse ? "mean MSE (older record)" : "mean of frames";
}

std::string Upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

double Median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

/// The finest level with a point, per lossy meshvid codec.
int FinestLevel(const BenchRecord& record, const std::string& codec) {
  int finest = -1;
  for (const BenchPoint& p : record.points) {
    if (p.method == kMethodMeshvid && p.codec == codec) finest = std::max(finest, p.level);
  }
  return finest;
}

/// The goal check of one record (issues 5 and 42): BD-rate <= -90% against the full
/// baseline and <= -60% against the decimated one at meshvid's vertex count, decoding >= 10x
/// faster, coverage never below the baseline's.
std::string GoalRow(const BenchRecord& record) {
  const BdRateEntry* best = nullptr;
  for (const BdRateEntry& b : record.bd_rates) {
    if (b.reference != kMethodBaseline) continue;
    if (b.ok && (best == nullptr || b.delta < best->delta)) best = &b;
  }
  std::vector<double> meshvid_fps, baseline_fps;
  double meshvid_coverage = std::numeric_limits<double>::infinity();
  double baseline_coverage = -1;
  for (const BenchPoint& p : record.points) {
    if (!p.ok) continue;
    if (p.method == kMethodBaseline) {
      baseline_fps.push_back(p.decode_fps);
      baseline_coverage = std::max(baseline_coverage, p.coverage);
    } else if (p.method == kMethodMeshvid && p.codec != "ffv1" &&
               p.level == FinestLevel(record, p.codec)) {
      meshvid_fps.push_back(p.decode_fps);
      meshvid_coverage = std::min(meshvid_coverage, p.coverage);
    }
  }
  const double speedup = Median(meshvid_fps) / Median(baseline_fps);
  std::string row = "| " + record.sequence + " | " + record.rig + " | ";
  row += best ? Percent(best->delta) + " (" + Upper(best->codec) + " L" +
                    std::to_string(best->level) + ")" + (best->delta <= -0.9 ? " met" : " not met")
              : std::string(record.bd_rates.empty() ? "n/a" : "n/a (see below)");
  // Against the decimated baseline at meshvid's own vertex count (issue 42: <= -60%).
  const BdRateEntry* decimated = nullptr;
  const std::string same_size = std::string(kMethodDecimated) + " " + DecimatedCodecName(1.0);
  for (const BdRateEntry& b : record.bd_rates) {
    if (b.reference == same_size && b.ok && (decimated == nullptr || b.delta < decimated->delta))
      decimated = &b;
  }
  row += " | " + (decimated ? Percent(decimated->delta) + " (" + Upper(decimated->codec) + " L" +
                                  std::to_string(decimated->level) + ")" +
                                  (decimated->delta <= -0.6 ? " met" : " not met")
                            : std::string("n/a"));
  row += " | " + (std::isfinite(speedup)
                      ? Fmt("%.1fx", speedup) + (speedup >= 10 ? " met" : " not met")
                      : std::string("n/a"));
  const bool have_coverage = std::isfinite(meshvid_coverage) && baseline_coverage >= 0;
  row += " | " + (have_coverage ? Fmt("%.1f%%", 100 * meshvid_coverage) + " vs " +
                                      Fmt("%.1f%%", 100 * baseline_coverage) +
                                      (meshvid_coverage >= baseline_coverage ? " met" : " not met")
                                : std::string("n/a"));
  return row + " |\n";
}

std::string MetMark(bool met) { return met ? " met" : " missed"; }

/// The row of a table about `record` when its simulation failed: sequence, rig, the failure,
/// and `empty_cells` empty cells after it.
std::string SimulationFailedRow(const BenchRecord& record, int empty_cells) {
  std::string row = "| " + record.sequence + " | " + record.rig + " | simulation failed";
  for (int i = 0; i <= empty_cells; ++i) row += " |";
  return row + "\n";
}

/// The divergence row of one record (its check computed from its points, so a record written
/// before the check was recorded has one too); its note, if any, goes to `notes`.
std::string DivergenceRow(const BenchRecord& record, std::string* notes) {
  if (!record.simulate_ok) return SimulationFailedRow(record, 4);
  std::string row = "| " + record.sequence + " | " + record.rig + " | ";
  BenchRecord copy = record;
  ComputeDivergence(copy);
  const DivergenceCheck& d = copy.divergence;
  if (!d.note.empty()) *notes += "- " + record.sequence + " " + record.rig + ": " + d.note + "\n";
  row += Upper(d.codec) + " q" + std::to_string(d.quality) +
         (d.level >= 0 ? " L" + std::to_string(d.level) : std::string()) +
         (d.has_default ? "" : " (n/a)") + " | ";
  row += (d.has_baseline ? std::to_string(d.baseline_bits) + " bits" : std::string("n/a")) + " | ";
  if (!d.has_default || !d.has_baseline) return row + "n/a | n/a | n/a |\n";
  if (d.has_frames) {
    row += std::to_string(d.frames_within) + "/" + std::to_string(d.frames) + " (" +
           Fmt("%.1f%%", 100 * d.share_within) + ")" + MetMark(d.share_met) + " | ";
    row += std::to_string(d.worst_frame) + ": " + Fmt("%.3g", d.worst_ratio) + "x (" +
           Fmt("%.3g", 1e3 * d.worst_meshvid_accuracy_rms) + " vs " +
           Fmt("%.3g", 1e3 * d.worst_baseline_accuracy_rms) + ") | ";
  } else {
    row += "n/a (no per-frame figures) | n/a | ";
  }
  row += Fmt("%.2f", d.meshvid_d1_psnr) + " vs " + Fmt("%.2f", d.baseline_d1_psnr) + " dB" +
         (d.psnr == kPsnrOfMeanMse ? " (mean MSE, older record)" : "") + MetMark(d.psnr_met);
  return row + " |\n";
}

/// The "Divergence" section: one row per record.
std::string DivergenceSection(const std::vector<BenchRecord>& records) {
  std::string md =
      "## Divergence\n\n"
      "meshvid at the encoder's default settings (" +
      Upper(DefaultCodecName()) + ", quality " + std::to_string(DefaultQuality()) +
      ", decoded at the finest level its file stores) against the baseline's best setting (the "
      "Draco position bits with the highest D1 PSNR, mean of frames), frame by frame: ratio = "
      "meshvid's accuracy RMS / the baseline's on the same frame. Goals: the ratio is at most " +
      Fmt("%.3g", kDivergenceRatioLimit) + " on at least " +
      Fmt("%.0f%%", 100 * kDivergenceShareGoal) +
      " of the frames, and meshvid's D1 PSNR (mean of frames) is at least the baseline best's. "
      "Worst frame: the frame with the highest ratio (0-based), its ratio and both accuracies "
      "(RMS, 10^-3 data units).\n\n";
  md += "| sequence | rig | default point | baseline best | frames within " +
        Fmt("%.3g", kDivergenceRatioLimit) +
        "x | worst frame: ratio (meshvid vs baseline accuracy) | D1 PSNR, mean of frames: "
        "default vs baseline best |\n";
  md += "|---|---|---|---|---|---|---|\n";
  std::string notes;
  for (const BenchRecord& r : records) md += DivergenceRow(r, &notes);
  md += "\n";
  if (!notes.empty()) md += notes + "\n";
  return md;
}

/// The colour row of one record: the default point's colour against the baseline best's (the
/// same setting the divergence check takes; its colour is 8 bits a channel at every setting).
std::string ColourRow(const BenchRecord& record) {
  std::string row = "| " + record.sequence + " | " + record.rig + " | ";
  const BenchPoint* meshvid = FindDefaultPoint(record);
  const BenchPoint* baseline = FindBaselineBest(record);
  const auto has_colour = [](const BenchPoint* p) {
    return p != nullptr && p->ok && !std::isnan(p->y_psnr) &&
           !std::isnan(p->colour_bytes_per_frame);
  };
  if (!has_colour(meshvid) || !has_colour(baseline)) {
    return row + "n/a (no colour measured) | | | | |\n";
  }
  const double psnr_gap = meshvid->y_psnr - baseline->y_psnr;
  const double bytes_ratio =
      baseline->colour_bytes_per_frame > 0
          ? meshvid->colour_bytes_per_frame / baseline->colour_bytes_per_frame
          : std::numeric_limits<double>::quiet_NaN();
  const double share = meshvid->bytes_per_frame > 0
                           ? meshvid->colour_bytes_per_frame / meshvid->bytes_per_frame
                           : std::numeric_limits<double>::quiet_NaN();
  row += Fmt("%.2f", meshvid->y_psnr) + " vs " + Fmt("%.2f", baseline->y_psnr) + " dB (" +
         Fmt("%+.2f", psnr_gap) + ")" + MetMark(psnr_gap >= -kColourPsnrGapGoal) + " | ";
  row += Fmt("%.0f", meshvid->colour_bytes_per_frame) + " vs " +
         Fmt("%.0f", baseline->colour_bytes_per_frame) + " | ";
  row += Fmt("%.3g", bytes_ratio) + "x" + MetMark(bytes_ratio <= kColourBytesRatioGoal) + " | ";
  row += Fmt("%.1f%%", 100 * share) + MetMark(share <= kColourShareGoal) + " | ";
  row += Fmt("%.2f", meshvid->yuv_psnr) + " vs " + Fmt("%.2f", baseline->yuv_psnr) + " dB |\n";
  return row;
}

/// The "Colour" section: one row per record.
std::string ColourSection(const std::vector<BenchRecord>& records) {
  std::string md =
      "## Colour\n\n"
      "The default point's colour (`meshvid eval`: PSNR of 8-bit BT.709 Y against the ground "
      "truth's colour at the nearest surface point, eval's mean row) and colour stream "
      "against the baseline best's (the divergence check's setting: the fused mesh's "
      "per-vertex colour as a Draco attribute of 8 bits a channel; its colour bytes are each "
      "frame coded with and without the attribute, the difference). Goals (issue 44): Y PSNR "
      "within " +
      Fmt("%.3g", kColourPsnrGapGoal) + " dB of the baseline's, at most " +
      Fmt("%.3g", kColourBytesRatioGoal) + "x its colour bytes, colour at most " +
      Fmt("%.0f%%", 100 * kColourShareGoal) + " of meshvid's file.\n\n";
  md +=
      "| sequence | rig | Y PSNR: default vs baseline best | colour bytes/frame: default vs "
      "baseline best | colour bytes ratio | colour share of the file | YUV PSNR (6:1:1): default "
      "vs baseline best |\n";
  md += "|---|---|---|---|---|---|---|\n";
  for (const BenchRecord& r : records) {
    md += r.simulate_ok ? ColourRow(r) : SimulationFailedRow(r, 4);
  }
  return md + "\n";
}

std::string PointRow(const BenchPoint& p) {
  const bool baseline = p.method != kMethodMeshvid;
  std::string setting = std::to_string(p.quality);
  setting = baseline ? setting + " bits" : "q" + setting;
  std::string row = "| " + p.method;
  row += " | " + Upper(p.codec) + " | " + setting;
  if (p.method == kMethodDecimated) row += Fmt(", %.0f vertices", p.vertices);
  row += " | ";
  row += baseline ? std::string("-") : std::to_string(p.level);
  row += " | ";
  if (!p.ok) return row + "failed | | | | | | | | | | | | | | |\n";
  row += Fmt("%.0f", p.bytes_per_frame) + " | " + Fmt("%.3g", p.mbit_per_s) + " | " +
         Fmt("%.2f", p.d1_psnr_mean_of_frames) + " | " + Fmt("%.2f", p.d1_psnr) + " | " +
         Fmt("%.2f", p.d2_psnr_mean_of_frames) + " | " + Fmt("%.2f", p.d2_psnr) + " | " +
         Fmt("%.3g", 1e3 * p.accuracy_rms) + " | " + Fmt("%.3g", 1e3 * p.completeness_rms) + " | " +
         Fmt("%.1f%%", 100 * p.coverage) + " | " + Fmt("%.3g", p.encode_fps) + " | " +
         Fmt("%.3g", p.decode_fps) + " | " + Fmt("%.0f", p.encode_peak_mb) + " | " +
         Fmt("%.0f", p.decode_peak_mb) + " | " +
         (std::isnan(p.colour_bytes_per_frame) ? std::string("-")
                                               : Fmt("%.0f", p.colour_bytes_per_frame)) +
         " | " + (std::isnan(p.y_psnr) ? std::string("-") : Fmt("%.2f", p.y_psnr)) + " |\n";
  return row;
}

std::string RecordSection(const BenchRecord& record, const ReportOptions& options) {
  const std::string name = BenchRecordName(record);
  std::string md = "## " + record.sequence + ", " + std::to_string(record.views) + " views (" +
                   record.layout + ")\n\n";
  md += "Ground truth `" + record.ground_truth + "`, " + std::to_string(record.frames) +
        " frames at " + Fmt("%g", record.frame_rate) + " fps, " +
        std::to_string(record.eval_samples) + " samples per surface; measured " + record.date +
        " (peak memory floor: the bench process's own " +
        Fmt("%.0f", record.bench_process_peak_mb) + " MB). Record: `" + name + ".json`.\n\n";
  if (!record.encode_args.empty()) {
    md += "Every meshvid encode of this record was given `" + record.encode_args + "`.\n\n";
  }
  if (!record.simulate_ok) {
    return md + "**Simulation failed**, nothing else ran: " + record.simulate_error + "\n\n";
  }
  const std::string psnr_kind = RecordPsnrKind(record);
  const auto plot = options.plots.find(name);
  if (plot != options.plots.end()) {
    md += "![D1 PSNR, " + PsnrKindLabel(psnr_kind) + ", against rate, " + name + "](" +
          plot->second + ")\n\n";
  } else if (!options.plot_note.empty()) {
    md += "(No plot: " + options.plot_note + ")\n\n";
  }
  const auto still = options.stills.find(name);
  if (still != options.stills.end()) {
    const DivergenceCheck& d = record.divergence;
    md += "The default point's worst frame (" +
          (d.has_frames && d.worst_frame >= 0 ? "frame " + std::to_string(d.worst_frame)
                                              : std::string("frame 0: no per-frame figures")) +
          "): input views | decoded | ground truth, coloured by distance to the ground truth "
          "(`meshvid render`; the baseline's decoded frames are not kept, so it is not shown):"
          "\n\n![worst frame, " + name + "](" + still->second + ")\n\n";
  }
  if (!record.bd_rates.empty()) {
    md +=
        "BD-rate against each baseline curve (bytes per frame at equal D1 PSNR, the D1 PSNR "
        "named in the table; negative = fewer bytes): the full fused mesh, and the fused mesh "
        "decimated to 1/2, 1 and 2 times the vertices meshvid decodes at its default "
        "setting:\n\n";
    md += "| reference | codec | level | BD-rate | D1 PSNR | over D1 PSNR | note |\n";
    md += "|---|---|---|---|---|---|---|\n";
    for (const BdRateEntry& b : record.bd_rates) {
      md += "| " + b.reference + " | " + Upper(b.codec) + " | " + std::to_string(b.level) + " | " +
            (b.ok ? "**" + Percent(b.delta) + "**" : std::string("n/a")) + " | " +
            PsnrKindLabel(b.psnr) + " | " +
            (b.ok ? Fmt("%.2f", b.psnr_low) + " - " + Fmt("%.2f", b.psnr_high) + " dB" : "") +
            " | " + b.note + " |\n";
    }
    md += "\n";
  }
  md +=
      "| method | codec | setting | level | bytes/frame | Mbit/s | D1 PSNR, mean of frames | "
      "D1 PSNR, mean MSE | D2 PSNR, mean of frames | D2 PSNR, mean MSE | accuracy RMS (1e-3) | "
      "completeness RMS (1e-3) | coverage | encode fps | decode fps | encode MB | decode MB | "
      "colour bytes/frame | Y PSNR |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<BenchPoint> points = record.points;
  std::stable_sort(points.begin(), points.end(), [](const BenchPoint& a, const BenchPoint& b) {
    if (a.method != b.method) {
      // The full baseline, the decimated baseline, then meshvid.
      auto order = [](const std::string& m) {
        return m == kMethodBaseline ? 0 : m == kMethodDecimated ? 1 : 2;
      };
      return order(a.method) < order(b.method);
    }
    if (a.codec != b.codec) return a.codec < b.codec;
    if (a.level != b.level) return a.level > b.level;
    return a.quality < b.quality;
  });
  for (const BenchPoint& p : points) md += PointRow(p);
  md += "\n";
  if (psnr_kind == kPsnrOfMeanMse) {
    md +=
        "This record predates the mean of per-frame PSNRs (n/a above, for some or all points): "
        "its BD-rates and plot use the D1 PSNR of the mean MSE. Running the same `meshvid "
        "bench` command again measures it.\n\n";
  }
  std::string failures;
  if (!record.baseline_ok && !record.baseline_error.empty()) {
    failures += "- baseline: " + record.baseline_error + "\n";
  }
  for (const BenchEncode& e : record.encodes) {
    if (!e.ok)
      failures += "- " + e.codec + " q" + std::to_string(e.quality) + ": " + e.error + "\n";
  }
  for (const BenchPoint& p : record.points) {
    if (!p.ok && p.method == kMethodMeshvid) {
      failures += "- " + p.codec + " q" + std::to_string(p.quality) + " level " +
                  std::to_string(p.level) + ": " + p.error + "\n";
    } else if (!p.ok && p.method == kMethodDecimated) {
      failures +=
          "- decimated " + p.codec + " " + std::to_string(p.quality) + " bits: " + p.error + "\n";
    }
  }
  if (!failures.empty())
    md += "Failed steps (re-run the same command to retry them):\n\n" + failures + "\n";

  md += "<details><summary>Commands of " + name + "</summary>\n\n```sh\n";
  std::set<std::string> seen;
  auto add = [&](const std::string& command) {
    if (!command.empty() && seen.insert(command).second) md += command + "\n";
  };
  add(record.simulate_command);
  add(record.baseline_command);
  // Every encode, then decode and eval of the first file only: the others differ in the
  // file name and level alone.
  for (const BenchEncode& e : record.encodes) {
    if (e.method == kMethodMeshvid) add(e.command);
  }
  std::string example;
  for (const BenchPoint& p : points) {
    if (p.method == kMethodMeshvid && example.empty() && p.commands.size() > 1) {
      example = p.codec + std::to_string(p.quality);
    }
    if (p.method == kMethodMeshvid && p.codec + std::to_string(p.quality) != example) continue;
    for (const std::string& c : p.commands) add(c);
  }
  md += "# ... and the same decode and eval commands for every other .mvid file and level.\n";
  md += "```\n\n</details>\n\n";
  return md;
}

}  // namespace

MachineInfo ReadMachineInfo() {
  MachineInfo info;
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos)
        info.cpu_model = line.substr(line.find_first_not_of(' ', colon + 1));
      break;
    }
  }
  info.cores = static_cast<int>(std::thread::hardware_concurrency());
  std::ifstream meminfo("/proc/meminfo");
  while (std::getline(meminfo, line)) {
    double kb = 0;
    if (std::sscanf(line.c_str(), "MemTotal: %lf kB", &kb) == 1) {
      info.ram_gb = kb * 1024 / 1e9;
      break;
    }
  }
  struct utsname name {};
  if (uname(&name) == 0)
    info.kernel = std::string(name.sysname) + " " + name.release + " " + name.machine;
  return info;
}

std::string BenchStillName(const BenchRecord& record) {
  return BenchRecordName(record) + "-still.png";
}

std::string GenerateResultsMarkdown(const std::vector<BenchRecord>& records,
                                    const ReportOptions& options) {
  std::string md = "# meshvid bench: results\n\n";
  md += "Generated by `meshvid bench` on " + options.date +
        "; do not edit by hand (run `meshvid bench --report-only` to regenerate it from the "
        "records in `results/`).\n\n";
  if (!options.command_line.empty()) md += "    " + options.command_line + "\n\n";
  std::set<std::string> machines;
  for (const BenchRecord& r : records) {
    machines.insert(r.machine.cpu_model + ", " + std::to_string(r.machine.cores) + " cores, " +
                    Fmt("%.1f", r.machine.ram_gb) + " GB RAM, " + r.machine.kernel);
  }
  md += "Machine: ";
  for (const std::string& m : machines) md += (m == *machines.begin() ? "" : "; ") + m;
  md += machines.empty() ? "none recorded.\n\n" : ".\n\n";

  md +=
      "## How it is measured\n\n"
      "- Each ground-truth sequence is captured by `meshvid simulate` with 3 views on a frontal "
      "arc and with 6 views on a ring; everything below runs on that capture and is measured "
      "against the simulated frames' ground truth with `meshvid eval` (the mean over frames; "
      "D1/D2 PSNR with peak p = the ground truth's bounding-box diagonal).\n"
      "- A sequence's D1/D2 PSNR is given two ways: **mean of frames**, the mean of the "
      "per-frame PSNRs (how MPEG's common test conditions average a sequence, so it compares "
      "with published figures; a frame counts as at most 100 dB), and **mean MSE**, the PSNR "
      "of the mean MSE over frames (lower: a few bad frames weigh more).\n"
      "- **meshvid**: `meshvid encode` at several qualities per codec (HEVC, AV1; FFV1 is the "
      "lossless reference, one point), each file decoded (`meshvid decode --no-write`) and "
      "evaluated at every level 0..L. Rate = the whole .mvid file.\n"
      "- **baseline** (what per-frame volumetric-video players stream): every frame's views "
      "fused on their own with the encoder's fusion (`FuseRangeMeshes`), the fused mesh coded "
      "with Draco (edgebreaker, position quantisation 8-14 bits, speed 0), decoded and "
      "evaluated the same way. Rate = the sum of the Draco bitstreams (no container).\n"
      "- **decimated** (what a per-frame player streams at a budgeted size): the baseline's "
      "fused mesh decimated (the encoder's quadric decimation) to 1/2, 1 and 2 times the "
      "vertices meshvid decodes at its default point (its mean per frame), then coded, "
      "decoded and evaluated as the baseline (8-12 bits; codec `draco 0.5x`, `1x`, `2x`). "
      "Encode fps counts the fusion and all three decimations.\n"
      "- Every point also records each frame's accuracy RMS and D1 PSNR (from its `meshvid "
      "eval --json`), which the Divergence table compares frame by frame.\n"
      "- Mbit/s at the capture's frame rate. Accuracy (test to ground truth) and completeness "
      "(ground truth to test) are RMS exact point-to-surface distances in 10^-3 data units "
      "(mm for metric data); coverage is the share of ground-truth samples within 0.25% of p "
      "of the test surface.\n"
      "- Speed: encode fps = frames / wall time of `meshvid encode` (process start and "
      "reading the capture included); the baseline's = frames / (reading + fusion + colour + Draco "
      "coding). Decode fps = frames / the decoder's own time for every frame, one thread "
      "(meshvid: `meshvid decode --no-write`, `MvidDecoder::DecodeFrame` to a full mesh, reading "
      "the file included; baseline: `meshvid bench-draco-decode`, Draco decoding of each "
      "frame's bitstream, reading excluded, which favours the baseline). Peak memory = the "
      "child process's peak resident set (wait4), which includes the small bench process's "
      "own at spawn; the baseline's encode memory is that of its one run (fusion and coding "
      "at every setting).\n"
      "- BD-rate: Bjontegaard delta rate of each meshvid codec and level (over its qualities) "
      "against the baseline and against each decimated curve, on D1 PSNR, mean of frames (a "
      "record written before that figure existed falls back to the D1 PSNR of the mean MSE, "
      "named in its BD-rate table): "
      "log10(bytes per frame) as a monotone piecewise-cubic "
      "(PCHIP, Fritsch-Carlson) function of PSNR, integrated over the PSNR interval both "
      "curves cover (the piecewise-cubic variant of VCEG-M33). n/a when the intervals do "
      "not overlap.\n\n";

  md +=
      "## Against the goal\n\n"
      "Goal (issue 5): at equal D1 PSNR meshvid needs 10x fewer bytes than the baseline "
      "(BD-rate <= -90%), decodes >= 10x faster, and is never worse in coverage; goal (issue "
      "42): BD-rate <= -60% against the baseline decimated to meshvid's decoded vertex count "
      "(decimated draco 1x). Best BD-rate over meshvid's curves; decode speed = median meshvid "
      "decode fps at the finest level over median baseline decode fps; coverage = the lowest "
      "meshvid coverage at the finest level "
      "against the best baseline coverage.\n\n";
  md +=
      "| sequence | rig | best BD-rate | best BD-rate vs decimated 1x | decode speed vs baseline "
      "| coverage: meshvid vs baseline |\n";
  md += "|---|---|---|---|---|---|\n";
  for (const BenchRecord& r : records) {
    md += r.simulate_ok ? GoalRow(r) : SimulationFailedRow(r, 3);
  }
  md += "\n";
  md += DivergenceSection(records);
  md += ColourSection(records);
  for (const BenchRecord& r : records) md += RecordSection(r, options);
  return md;
}

}  // namespace meshvid
