// `meshvid fuse`: the view fusion on its own. Fuses each frame of a capture into one surface
// (the fusion the encoder uses for its base meshes and `meshvid bench` for its baseline),
// optionally writes the surfaces, and reports failures, time per frame and peak memory.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "codec/common/progress.h"
#include "codec/enc/fusion/surface_fusion.h"
#include "format/output_file.h"
#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/option_checks.h"
#include "tools/cli/terminal.h"
#include "tools/io/capture.h"
#include "tools/io/file_pattern.h"
#include "tools/io/mesh_io.h"

namespace meshvid::cli {
namespace {

/// The command line of `meshvid fuse`.
struct FuseArguments {
  std::string capture;
  std::string output;
  std::string frames;
  std::string json;
  SurfaceFusionOptions fusion;
  bool quiet = false;
};

double PeakMemoryMegabytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return usage.ru_maxrss * 1024.0 / 1e6;  // ru_maxrss is in KiB on Linux
}

int RunFuse(const FuseArguments& args) {
  StatusOr<std::unique_ptr<CaptureSequence>> capture =
      CaptureSequence::OpenWithoutChecking(args.capture);
  if (!capture.ok()) return ReportError(capture.status());
  int first = 0, end = (*capture)->frame_count();
  if (!args.frames.empty()) {
    StatusOr<std::pair<int, int>> range = FramesOption(args.frames, end);
    if (!range.ok()) return ReportError(range.status());
    std::tie(first, end) = *range;
  }
  const Status files = (*capture)->CheckViewFiles(first, end);
  if (!files.ok()) return ReportError(files);
  std::optional<FilePattern> output;
  if (!args.output.empty()) {
    StatusOr<FilePattern> pattern = FilePattern::Parse(args.output);
    if (!pattern.ok()) return ReportError(pattern.status().WithContext("-o"));
    if (!pattern->has_frame() && end - first > 1) {
      return ReportError(InvalidArgumentError("-o " + args.output +
                                              ": several frames need a {frame} placeholder"));
    }
    output = *pattern;
  }

  ProgressBar bar(args.quiet);
  nlohmann::json frames = nlohmann::json::array();
  int failures = 0;
  double fuse_seconds = 0;
  for (int frame = first; frame < end; ++frame) {
    ReportProgress(bar.Callback(), "fuse", frame - first, end - first);
    nlohmann::json entry = {{"frame", frame}};
    StatusOr<std::vector<TriangleMesh>> views = (*capture)->LoadFrame(frame);
    if (!views.ok()) return ReportError(views.status());
    const auto start = std::chrono::steady_clock::now();
    StatusOr<TriangleMesh> fused = FuseRangeMeshes(*views, args.fusion);
    const double seconds = SecondsSince(start);
    fuse_seconds += seconds;
    entry["seconds"] = seconds;
    if (!fused.ok()) {
      ++failures;
      entry["error"] = ToValidUtf8(fused.status().ToString());
      bar.Message("frame " + std::to_string(frame) + ": " + fused.status().ToString());
    } else {
      entry["vertices"] = fused->vertex_count();
      entry["triangles"] = fused->triangle_count();
      if (output) {
        const Status written = WriteMesh(output->Expand(frame), *fused);
        if (!written.ok()) return ReportError(written);
      }
    }
    frames.push_back(std::move(entry));
  }
  ReportProgress(bar.Callback(), "fuse", end - first, end - first);
  bar.Finish();
  const int count = end - first;
  const double peak = PeakMemoryMegabytes();
  std::fprintf(stderr,
               "Fused frames %d..%d of %s: %d failed, %.3f s a frame (%.2f frames/s), peak "
               "memory %.0f MB\n",
               first, end - 1, args.capture.c_str(), failures, fuse_seconds / count,
               fuse_seconds > 0 ? count / fuse_seconds : 0.0, peak);
  if (!args.json.empty()) {
    const nlohmann::json summary = {{"capture", ToValidUtf8(args.capture)},
                                    {"frames", frames},
                                    {"failures", failures},
                                    {"fuse_seconds", fuse_seconds},
                                    {"peak_memory_mb", peak}};
    const Status written = WriteJsonOutput(args.json, DumpJson(summary, 2) + "\n");
    if (!written.ok()) return ReportError(written);
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace

void AddFuseCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<FuseArguments>();
  CLI::App* cmd = app.add_subcommand(
      "fuse",
      "Fuse each frame of a capture (its range views) into one surface: the fusion the\n"
      "encoder uses for its base meshes and meshvid bench for its per-frame baseline.\n"
      "Open data stays open, closed data comes out closed. Reports failures, time per\n"
      "frame and peak memory; exits 1 if any frame failed (the others are still fused).");
  cmd->add_option("capture", args->capture,
                  "Capture: manifest.json, .conf, or a {frame}+{view} pattern")
      ->required();
  cmd->add_option("-o,--out", args->output,
                  "Write the surfaces here, e.g. fused/f{frame:04}.ply (PLY or OBJ)");
  cmd->add_option("--frames", args->frames, "Frame range A:B (half-open), A:, :B or N")
      ->type_name("A:B");
  cmd->add_option("--json", args->json, JsonOptionHelp("Also write per-frame figures"))
      ->type_name("FILE|-");
  cmd->add_option("--voxel", args->fusion.spacing,
                  "Voxel size in the capture's units (default: from the views' sample spacing)")
      ->check(AtLeastZero());
  cmd->add_option("--max-points", args->fusion.max_points,
                  "Most input points used; denser views are thinned on a grid first")
      ->default_val(args->fusion.max_points)
      ->check(CLI::Range(std::size_t{100}, std::size_t{1} << 32));
  cmd->add_option("--truncation", args->fusion.truncation_voxels,
                  "Half-width of the band each point writes, in voxels")
      ->default_val(args->fusion.truncation_voxels)
      ->check(AboveZero());
  cmd->add_option("--support", args->fusion.support_voxels,
                  "The surface ends this many voxels past the edge of the data")
      ->default_val(args->fusion.support_voxels)
      ->check(AboveZero());
  cmd->add_option("--min-piece-share", args->fusion.min_piece_share,
                  "Drop connected pieces with fewer than this share of the triangles")
      ->default_val(args->fusion.min_piece_share)
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar (the report is still printed)");
  cmd->callback([args, exit_code] { *exit_code = RunFuse(*args); });
}

}  // namespace meshvid::cli
