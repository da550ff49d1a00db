// `meshvid bench`: meshvid against the per-frame baseline (fusion + Draco) on simulated
// captures, in one run: rate, error and speed, BD-rates, plots and bench/RESULTS.md.
// `meshvid bench-baseline` and `meshvid bench-draco-decode` (hidden) are the baseline's steps
// the bench runs as child processes.
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "format/output_file.h"
#include "tools/bench/baseline.h"
#include "tools/bench/bench_divergence.h"
#include "tools/bench/bench_report.h"
#include "tools/bench/bench_runner.h"
#include "tools/bench/child_process.h"
#include "tools/bench/eval_figures.h"
#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/terminal.h"
#include "tools/io/capture.h"

namespace meshvid::cli {
namespace {

namespace fs = std::filesystem;

/// The command line of `meshvid bench`.
struct BenchArguments {
  std::string sequences;
  std::string out = "bench/results";
  std::string work;
  std::string report;
  std::string rigs = "3-arc,6-ring";
  std::string codecs = "hevc,av1";
  std::string qualities = "20,40,60,80";
  std::string bits = "8,10,12,14";
  std::string decimated_bits = "8,10,12";
  bool no_decimated = false;
  std::string encode_args;
  int lossless_quality = 100;
  bool no_lossless = false;
  int frames = -1;    ///< -1: not given
  long samples = -1;  ///< -1: not given
  bool frames_given = false;
  bool samples_given = false;
  bool quick = false;
  bool fresh = false;
  bool keep_work = false;
  bool report_only = false;
  bool no_plots = false;
  bool no_stills = false;
  bool quiet = false;
};

/// The bench command as it would be typed to repeat this run.
std::string CommandLine(const BenchArguments& a, const BenchOptions& o) {
  std::vector<std::string> argv = {"meshvid", "bench"};
  if (!a.sequences.empty()) argv.insert(argv.end(), {"--sequences", a.sequences});
  if (a.quick) argv.push_back("--quick");
  argv.insert(argv.end(), {"-o", a.out});
  if (a.frames_given) argv.insert(argv.end(), {"--frames", std::to_string(a.frames)});
  if (a.samples_given) argv.insert(argv.end(), {"--samples", std::to_string(a.samples)});
  if (a.rigs != "3-arc,6-ring") argv.insert(argv.end(), {"--rigs", a.rigs});
  if (a.codecs != "hevc,av1") argv.insert(argv.end(), {"--codecs", a.codecs});
  if (a.qualities != "20,40,60,80") argv.insert(argv.end(), {"--qualities", a.qualities});
  if (a.bits != "8,10,12,14") argv.insert(argv.end(), {"--bits", a.bits});
  if (a.no_decimated) {
    argv.push_back("--no-decimated");
  } else if (a.decimated_bits != "8,10,12") {
    argv.insert(argv.end(), {"--decimated-bits", a.decimated_bits});
  }
  if (o.lossless_quality < 0) argv.push_back("--no-lossless");
  if (!a.encode_args.empty()) argv.insert(argv.end(), {"--encode-args", a.encode_args});
  return ShellQuoteCommand(argv);
}

/// Turns the arguments into BenchOptions (usage errors only).
Status BuildOptions(const BenchArguments& a, BenchOptions* o) {
  const std::string shared = DefaultSharedDataDir();
  std::string list = a.sequences;
  if (list.empty() && a.quick) list = shared.empty() ? "arm-block" : "samba";
  MESHVID_ASSIGN_OR_RETURN(o->sequences, ResolveBenchSequences(list, shared));
  MESHVID_ASSIGN_OR_RETURN(o->rigs, ParseRigList(a.rigs));
  MESHVID_ASSIGN_OR_RETURN(o->qualities, ParseIntList(a.qualities, 0, 100, "--qualities"));
  MESHVID_ASSIGN_OR_RETURN(o->position_bits, ParseIntList(a.bits, 1, 30, "--bits"));
  o->decimated_bits.clear();
  if (!a.no_decimated) {
    MESHVID_ASSIGN_OR_RETURN(o->decimated_bits,
                             ParseIntList(a.decimated_bits, 1, 30, "--decimated-bits"));
  }
  o->codecs.clear();
  std::size_t start = 0;
  while (start <= a.codecs.size()) {
    std::size_t end = a.codecs.find(',', start);
    if (end == std::string::npos) end = a.codecs.size();
    const std::string codec = a.codecs.substr(start, end - start);
    start = end + 1;
    if (codec != "hevc" && codec != "av1" && codec != "ffv1") {
      return InvalidArgumentError("--codecs '" + a.codecs +
                                  "': expected a comma-separated list of hevc, av1, ffv1");
    }
    o->codecs.push_back(codec);
  }
  if (a.frames_given && a.frames < 0) {
    return InvalidArgumentError("--frames must be >= 0 (0: every frame), got " +
                                std::to_string(a.frames));
  }
  if (a.samples_given && (a.samples < 1000 || a.samples > 100000000)) {
    return InvalidArgumentError("--samples must be at least 1000 (got " +
                                std::to_string(a.samples) + ")");
  }
  o->frames = a.frames_given ? a.frames : (a.quick ? 10 : 0);
  o->eval_samples =
      a.samples_given ? static_cast<std::size_t>(a.samples) : (a.quick ? 50000 : 200000);
  MESHVID_ASSIGN_OR_RETURN(o->encode_args, ParseEncodeArgs(a.encode_args));
  o->lossless_quality = a.no_lossless ? -1 : a.lossless_quality;
  o->results_dir = a.out;
  o->work_dir = a.work.empty() ? a.out + "/tmp" : a.work;
  o->resume = !a.fresh;
  o->keep_work = a.keep_work;
  o->draw_stills = !a.no_stills;
  std::error_code error;
  o->meshvid = fs::read_symlink("/proc/self/exe", error).string();
  if (error) return InternalError("cannot find this program's path: " + error.message());
  return Status::Ok();
}

/// Plots and RESULTS.md from every record in the results folder.
int WriteReport(const BenchArguments& args, const BenchOptions& options) {
  if (!fs::is_directory(options.results_dir)) {
    return ReportError(NotFoundError("no bench record in " + options.results_dir +
                                     " (no such folder): run meshvid bench first"));
  }
  StatusOr<std::vector<BenchRecord>> records = ReadBenchRecords(options.results_dir);
  if (!records.ok()) return ReportError(records.status());
  if (records->empty()) {
    return ReportError(
        NotFoundError("no bench record in " + options.results_dir + ": run meshvid bench first"));
  }
  // Records written before the per-frame figures: from the eval JSONs still in the work folder
  // (in memory only; the next bench run stores them).
  int filled = 0;
  for (BenchRecord& record : *records) {
    filled += BackfillFrameFigures(record, options.work_dir);
    ComputeDivergence(record);
  }
  if (filled > 0 && !args.quiet) {
    std::fprintf(stderr, "Per-frame figures of %d point(s) read from their eval JSON in %s\n",
                 filled, options.work_dir.c_str());
  }
  const std::string report =
      args.report.empty() ? (fs::path(options.results_dir).parent_path() / "RESULTS.md").string()
                          : args.report;
  const fs::path report_dir = fs::absolute(fs::path(report).parent_path());
  ReportOptions report_options;
  report_options.date = UtcTimestamp();
  report_options.command_line = CommandLine(args, options);
  if (args.no_plots) {
    report_options.plot_note = "plots were not drawn (--no-plots)";
  } else {
    StatusOr<std::map<std::string, std::string>> plots =
        RenderRdPlots(*records, options.results_dir, options.work_dir + "/logs");
    if (plots.ok()) {
      for (const auto& [name, png] : *plots) {
        report_options.plots[name] =
            fs::relative(fs::absolute(fs::path(options.results_dir) / png), report_dir).string();
      }
    } else {
      std::fprintf(stderr, "meshvid: plots skipped: %s\n", plots.status().message().c_str());
      report_options.plot_note = plots.status().message();
    }
  }
  for (const BenchRecord& record : *records) {
    const fs::path still = fs::path(options.results_dir) / BenchStillName(record);
    if (fs::exists(still)) {
      report_options.stills[BenchRecordName(record)] =
          fs::relative(fs::absolute(still), report_dir).string();
    }
  }
  const Status written = WriteFileAtomically(report, GenerateResultsMarkdown(*records, report_options));
  if (!written.ok()) return ReportError(written);
  if (!args.quiet)
    std::fprintf(stderr, "Wrote %s (%zu records)\n", report.c_str(), records->size());
  return 0;
}

int RunBenchCommand(const BenchArguments& args) {
  BenchOptions options;
  if (Status status = BuildOptions(args, &options); !status.ok()) {
    ReportError(status);
    return 2;
  }
  if (args.report_only) return WriteReport(args, options);

  ProgressBar bar(args.quiet);
  BenchEvents events;
  events.progress = bar.Callback();
  events.log = [&](const std::string& line) { bar.Message(line); };
  if (!args.quiet) {
    std::fprintf(stderr,
                 "meshvid bench: %zu sequence(s) x %zu rig(s), %s frames, %zu samples; "
                 "records in %s, work files in %s\n",
                 options.sequences.size(), options.rigs.size(),
                 options.frames > 0 ? std::to_string(options.frames).c_str() : "all",
                 options.eval_samples, options.results_dir.c_str(), options.work_dir.c_str());
  }
  StatusOr<std::vector<BenchRecord>> records = RunBench(options, events);
  bar.Finish();
  if (!records.ok()) return ReportError(records.status());
  int failed = 0;
  for (const BenchRecord& r : *records) {
    failed += !r.simulate_ok;
    for (const BenchEncode& e : r.encodes) failed += !e.ok;
    for (const BenchPoint& p : r.points) failed += !p.ok;
  }
  const int report = WriteReport(args, options);
  if (report != 0) return report;
  if (failed > 0) {
    std::fprintf(stderr,
                 "meshvid: %d step(s) failed; they are listed in the records and in the "
                 "report. Run the same command again to retry only those.\n",
                 failed);
    return 1;
  }
  return 0;
}

/// The command line of the hidden `meshvid bench-baseline`.
struct BaselineArguments {
  std::string capture;
  std::string out;
  std::string bits = "8,10,12,14";
  std::string decimate;
  std::string summary_json;
  int draco_speed = 0;
  bool no_colour = false;
  bool quiet = false;
};

int RunBaselineCommand(const BaselineArguments& args) {
  BaselineOptions options;
  StatusOr<std::vector<int>> bits = ParseIntList(args.bits, 1, 30, "--bits");
  if (!bits.ok()) {
    ReportError(bits.status());
    return 2;
  }
  options.position_bits = *bits;
  if (!args.decimate.empty()) {
    StatusOr<std::vector<int>> targets =
        ParseIntList(args.decimate, 4, std::numeric_limits<int>::max(), "--decimate");
    if (!targets.ok()) {
      ReportError(targets.status());
      return 2;
    }
    options.vertex_targets.assign(targets->begin(), targets->end());
  }
  options.draco_speed = args.draco_speed;
  options.colour = !args.no_colour;
  options.out_dir = args.out;
  StatusOr<std::unique_ptr<CaptureSequence>> capture = CaptureSequence::Open(args.capture);
  if (!capture.ok()) return ReportError(capture.status());
  ProgressBar bar(args.quiet);
  StatusOr<BaselineSummary> summary = RunBaseline(**capture, options, bar.Callback());
  bar.Finish();
  if (!summary.ok()) return ReportError(summary.status());
  if (!args.summary_json.empty()) {
    const Status written = WriteJsonOutput(args.summary_json, BaselineSummaryToJson(*summary));
    if (!written.ok()) return ReportError(written);
  }
  if (!args.quiet) {
    std::fprintf(
        stderr,
        "Baseline on %d frames: reading %.2f s, fusion %.2f s, decimation %.2f s, colour %.2f s\n",
        summary->frames, summary->load_seconds, summary->fuse_seconds, summary->decimate_seconds,
        summary->colour_seconds);
    for (const BaselineSetting& s : summary->settings) {
      const std::string mesh = s.target_vertices == 0
                                   ? std::string("full")
                                   : "to " + std::to_string(s.target_vertices) + " vertices";
      std::fprintf(stderr,
                   "  %s, %2d bits: %.0f bytes/frame (colour %.0f), Draco encode %.3f s, decode "
                   "%.3f s, %.0f vertices/frame -> %s\n",
                   mesh.c_str(), s.position_bits,
                   summary->frames ? double(s.bytes_total) / summary->frames : 0.0,
                   summary->frames ? double(s.colour_bytes_total) / summary->frames : 0.0,
                   s.encode_seconds, s.decode_seconds, s.vertices, s.pattern.c_str());
    }
  }
  return 0;
}

/// `meshvid bench-draco-decode FOLDER`: the baseline player's decoding, timed.
int RunDracoDecodeCommand(const std::string& folder, const std::string& json, bool quiet) {
  StatusOr<DracoDecodeSummary> summary = DecodeDracoFrames(folder);
  if (!summary.ok()) return ReportError(summary.status());
  const double fps = summary->seconds > 0 ? summary->frames / summary->seconds : 0.0;
  if (!json.empty()) {
    const nlohmann::json j = {{"folder", folder},
                              {"frames", summary->frames},
                              {"bytes_total", summary->bytes_total},
                              {"seconds", summary->seconds},
                              {"frames_per_second", fps},
                              {"vertices", summary->vertices}};
    const Status written = WriteJsonOutput(json, DumpJson(j, 2) + "\n");
    if (!written.ok()) return ReportError(written);
  }
  if (!quiet) {
    std::fprintf(stderr,
                 "Decoded %d Draco frames of %s in %.3f s: %.1f frames/s, %.0f vertices/frame\n",
                 summary->frames, folder.c_str(), summary->seconds, fps, summary->vertices);
  }
  return 0;
}

}  // namespace

void AddBenchCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<BenchArguments>();
  CLI::App* cmd = app.add_subcommand(
      "bench",
      "Measure meshvid against the per-frame baseline (each frame's views fused and coded\n"
      "with Draco, as volumetric-video players stream) on simulated captures of each\n"
      "ground-truth sequence with 3 views on an arc and 6 on a ring: meshvid encode at\n"
      "several qualities per codec (HEVC, AV1; FFV1 lossless), decoded and evaluated at every\n"
      "level; the baseline at several Draco quantisations, in full and decimated to 1/2, 1 and\n"
      "2 times meshvid's decoded vertex count, evaluated the same way (with the views' colour\n"
      "per vertex where the capture has colour). Records bytes/frame, Mbit/s, D1/D2 PSNR,\n"
      "accuracy, completeness, coverage, colour (Y PSNR, colour bytes), encode/decode frames/s\n"
      "and peak memory per point in OUT/<sequence>-<rig>.json, BD-rates (D1) against each "
      "baseline\n"
      "curve, RD plots (gnuplot) and RESULTS.md beside OUT. Every step is a child\n"
      "process of this program; a failing step is recorded and the run goes on; running the\n"
      "same command again resumes (finished steps are kept). A full run takes hours;\n"
      "--quick takes minutes.");
  cmd->add_option("--sequences", args->sequences,
                  "Comma-separated: names in the shared data (samba, horse-gallop,\n"
                  "chickenCrossing), scenes (arm-block, cloth) or ground-truth paths\n"
                  "(default: all of them; --quick: samba, or arm-block without shared data)");
  cmd->add_flag("--quick", args->quick,
                "CI-sized run: first 10 frames, 50,000 eval samples, one sequence");
  cmd->add_option("-o,--out", args->out, "Folder of the records and plots")->capture_default_str();
  cmd->add_option("--work", args->work,
                  "Folder of captures, .mvid files and logs (default: OUT/tmp)");
  cmd->add_option("--report", args->report, "The generated report (default: OUT/../RESULTS.md)");
  cmd->add_option("--frames", args->frames,
                  "Capture frames per sequence, 0: all (default: all; "
                  "--quick: 10)")
      ->type_name("N");
  cmd->add_option("--samples", args->samples,
                  "meshvid eval samples per surface (default 200000; --quick: 50000)");
  cmd->add_option("--rigs", args->rigs, "Rigs as VIEWS-LAYOUT")->capture_default_str();
  cmd->add_option("--codecs", args->codecs, "Lossy meshvid codecs, one curve each")
      ->capture_default_str();
  cmd->add_option("--qualities", args->qualities, "meshvid encode --quality values (0..100)")
      ->capture_default_str();
  cmd->add_option("--bits", args->bits, "Baseline Draco position bits")->capture_default_str();
  cmd->add_option("--decimated-bits", args->decimated_bits,
                  "Draco position bits of the decimated baseline: each frame's fused mesh "
                  "decimated to 1/2, 1 and 2 times the vertices meshvid decodes at its default "
                  "setting, as per-frame players stream a mesh of a budgeted size")
      ->capture_default_str();
  cmd->add_flag("--no-decimated", args->no_decimated, "Do not run the decimated baseline");
  cmd->add_option("--lossless-quality", args->lossless_quality,
                  "Quality of the one FFV1 (lossless reference) point")
      ->capture_default_str();
  cmd->add_flag("--no-lossless", args->no_lossless, "Skip the FFV1 reference point");
  cmd->add_option(
      "--encode-args", args->encode_args,
      "Extra arguments of every meshvid encode, split at spaces, e.g. '--rebase-gain 4':\n"
      "a setting measured against the baseline as the defaults are. A record made\n"
      "with other extra arguments starts afresh: give such a run its own -o and\n"
      "--report (e.g. -o bench/results-gain4 --report bench/RESULTS-gain4.md)");
  cmd->add_flag("--fresh", args->fresh, "Redo every step instead of resuming");
  cmd->add_flag("--keep-work", args->keep_work,
                "Keep the baseline's decoded frames (large) after evaluating them");
  cmd->add_flag("--report-only", args->report_only,
                "Only redraw the plots and RESULTS.md from the records in OUT (per-frame\n"
                "figures older records lack are read from the eval JSON in the work folder)");
  cmd->add_flag("--no-plots", args->no_plots, "Do not run gnuplot");
  cmd->add_flag("--no-stills", args->no_stills,
                "Do not draw each record's worst frame with meshvid render");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar and no step lines");
  cmd->callback([args, exit_code, cmd] {
    args->frames_given = cmd->count("--frames") > 0;
    args->samples_given = cmd->count("--samples") > 0;
    *exit_code = RunBenchCommand(*args);
  });

  auto baseline = std::make_shared<BaselineArguments>();
  CLI::App* base = app.add_subcommand(
      "bench-baseline",
      "The per-frame baseline step of meshvid bench: fuse each frame's views, code the fused\n"
      "mesh (or, with --decimate, the fused mesh decimated to each vertex count) with Draco\n"
      "(edgebreaker) at each --bits, decode it and write the decoded frames to\n"
      "OUT/b<bits>/f<frame:04>.ply (decimated: OUT/v<vertices>-b<bits>/...). A capture with\n"
      "colour gives every coded mesh the views' colour per vertex, coded by Draco as 8 bits\n"
      "per channel, its bytes counted apart.");
  base->group("");  // hidden: meshvid bench runs it
  base->add_option("CAPTURE", baseline->capture, "The capture (manifest.json, pattern, .conf)")
      ->required();
  base->add_option("-o,--out", baseline->out, "Output folder")->required();
  base->add_option("--bits", baseline->bits, "Draco position bits")->capture_default_str();
  base->add_option("--decimate", baseline->decimate,
                   "Decimate each fused frame to each of these vertex counts (N,N,...) before "
                   "coding; without it the full fused mesh is coded")
      ->type_name("N,...");
  base->add_option("--draco-speed", baseline->draco_speed, "Draco speed 0 (smallest) .. 10")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  base->add_option("--json,--summary-json", baseline->summary_json,
                   JsonOptionHelp("Write the measurements"))
      ->type_name("FILE|-");
  base->add_flag("--no-colour", baseline->no_colour,
                 "Code positions and triangles only, even when the capture has colour");
  base->add_flag("-q,--quiet", baseline->quiet, "No progress bar and no summary");
  base->callback([baseline, exit_code] { *exit_code = RunBaselineCommand(*baseline); });

  struct DracoDecodeArguments {
    std::string folder, json;
    bool quiet = false;
  };
  auto decode = std::make_shared<DracoDecodeArguments>();
  CLI::App* draco = app.add_subcommand(
      "bench-draco-decode",
      "The baseline player of meshvid bench: decode every f<frame>.drc of FOLDER with Draco,\n"
      "timing the decoding alone.");
  draco->group("");  // hidden: meshvid bench runs it
  draco->add_option("FOLDER", decode->folder, "Folder of .drc files")->required();
  draco->add_option("--json", decode->json, JsonOptionHelp("Write the timing"))
      ->type_name("FILE|-");
  draco->add_flag("-q,--quiet", decode->quiet, "No summary");
  draco->callback([decode, exit_code] {
    *exit_code = RunDracoDecodeCommand(decode->folder, decode->json, decode->quiet);
  });
}

}  // namespace meshvid::cli
