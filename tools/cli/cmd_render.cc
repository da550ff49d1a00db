// `meshvid render`: pictures of a .mvid, a capture or ground truth (Embree ray casting), side
// by side, optionally coloured by distance to ground truth, as PNG or MP4.
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/mvid_input.h"
#include "tools/cli/option_checks.h"
#include "tools/cli/terminal.h"
#include "tools/io/file_pattern.h"
#include "tools/render/render_job.h"

namespace meshvid::cli {
namespace {

struct RenderArguments {
  std::string input;
  std::vector<std::string> compare;
  std::string output;
  std::string frames;
  int level = -1;
  std::string camera;
  std::string size = "640x480";
  std::string error_against;
  float error_max_mm = 0;
  int crf = 20;
  bool no_labels = false;
  bool quiet = false;
  bool allow_partial = false;
  std::string json;
};

int RunRender(const RenderArguments& args) {
  RenderJobOptions options;
  options.inputs.push_back(args.input);
  options.inputs.insert(options.inputs.end(), args.compare.begin(), args.compare.end());
  options.output = args.output;
  options.level = args.level;
  options.allow_partial = args.allow_partial;
  if (args.allow_partial) {
    for (const std::string& input : options.inputs) WarnIfPartial(input);
    WarnIfPartial(args.error_against);
  }
  options.error_against = args.error_against;
  options.error_max_mm = args.error_max_mm;
  options.labels = !args.no_labels;
  options.crf = args.crf;
  if (std::sscanf(args.size.c_str(), "%dx%d", &options.width, &options.height) != 2) {
    std::fprintf(stderr, "meshvid: --size takes WxH, e.g. 640x480\n");
    return 2;
  }
  if (!args.camera.empty()) {
    StatusOr<OrbitSpec> orbit = ParseOrbitSpec(args.camera);
    if (!orbit.ok()) return ReportError(orbit.status().WithContext("--camera"));
    options.orbit = *orbit;
  }
  if (!args.frames.empty()) {
    StatusOr<std::pair<int, int>> range =
        FramesOption(args.frames, std::numeric_limits<int>::max());
    if (!range.ok()) return ReportError(range.status());
    options.first_frame = range->first;
    // "A:" (to the end) parses as A:INT_MAX: render as many as every input has.
    options.end_frame = range->second == std::numeric_limits<int>::max() ? -1 : range->second;
  }
  ProgressBar bar(args.quiet);
  StatusOr<RenderJobStats> stats = RunRenderJob(options, bar.Callback());
  bar.Finish();
  if (!stats.ok()) return ReportError(stats.status());
  if (!args.json.empty()) {
    const nlohmann::json j = {{"file", ToValidUtf8(args.output)},
                              {"frames", stats->frames},
                              {"width", stats->width},
                              {"height", stats->height},
                              {"seconds", stats->seconds},
                              {"error_max_mm", stats->error_max_mm},
                              {"video_codec", stats->video_codec}};
    const Status written = WriteJsonOutput(args.json, DumpJson(j, 2) + "\n");
    if (!written.ok()) return ReportError(written);
  }
  if (!stats->clipped_frames.empty()) {
    std::fprintf(stderr, "meshvid: warning: --frames: %s\n", stats->clipped_frames.c_str());
  }
  if (!args.quiet) {
    std::fprintf(stderr, "Rendered %s of %dx%d in %.2f s (%.1f frames/s) to %s%s%s",
                 Count(stats->frames, "frame").c_str(), stats->width, stats->height, stats->seconds,
                 stats->seconds > 0 ? stats->frames / stats->seconds : 0.0, args.output.c_str(),
                 stats->video_codec.empty() ? "" : " with ", stats->video_codec.c_str());
    if (!args.error_against.empty()) {
      std::fprintf(stderr, "; colour scale 0..%.3g mm", stats->error_max_mm);
    }
    std::fprintf(stderr, "\n");
  }
  return 0;
}

}  // namespace

void AddRenderCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<RenderArguments>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render surfaces to a picture or a video: Embree ray casting, shaded, seen from a camera\n"
      "that frames INPUT over the frames rendered (y up). INPUT and every --compare input is\n"
      "a panel, left to right, all seen from the same camera:\n"
      "  a .mvid (decoded at --level), a capture (manifest.json, a {view} pattern, a .conf:\n"
      "  the raw views of each frame together), or ground truth (NAME.obj + NAME.pc2, a\n"
      "  folder of meshes, a {frame} pattern, scene:arm-block, scene:cloth).\n"
      "-o OUT.png renders the first frame of --frames; OUT{frame:04}.png one PNG per frame;\n"
      "OUT.mp4 every frame as H.264 (HEVC where FFmpeg lacks libx264), yuv420p.\n"
      "Example: meshvid render cap/manifest.json --compare samba.mvid --compare samba.obj\n"
      "         --error-against samba.obj --frames 10:11 -o compare.png");
  cmd->add_option("INPUT", args->input, "What to render (first panel)")->required();
  cmd->add_option("-o,--out", args->output, "OUT.png, OUT{frame:04}.png or OUT.mp4")->required();
  cmd->add_option("--compare", args->compare,
                  "Another input shown beside INPUT (repeat for more panels)")
      ->allow_extra_args(false);
  cmd->add_option("--frames", args->frames,
                  "Frame range A:B (half-open), A:, :B or N (default: all; a single PNG shows\n"
                  "the first)")
      ->type_name("A:B");
  cmd->add_option("--level", args->level,
                  "Level of .mvid inputs, 0 (base) .. L (default: the finest stored)")
      ->check(AtLeastZero());
  cmd->add_option("--camera", args->camera,
                  "AZ,EL[,ZOOM]: azimuth about +y and elevation in degrees, zoom > 1 closer\n"
                  "(default 25,12,1: from the front (+z), a little right and above)");
  cmd->add_option("--size", args->size, "Size of each panel, WxH (default 640x480)");
  cmd->add_option("--error-against", args->error_against,
                  "Ground truth: colour every other panel by each vertex's distance to it,\n"
                  "with a colour bar in millimetres (scene units taken as metres)");
  cmd->add_option("--error-max", args->error_max_mm,
                  "Top of the error colour scale in mm (default: a round number above 4 times\n"
                  "the first frame's median distance, in the worst panel)")
      ->check(AboveZero());
  cmd->add_option("--crf", args->crf, "MP4 quality, x264/x265 CRF 0..51 (default 20)")
      ->check(CLI::Range(0, 51));
  cmd->add_flag("--no-labels", args->no_labels, "No panel names or frame number");
  cmd->add_option("--json", args->json, JsonOptionHelp("Also write what was drawn"))
      ->type_name("FILE|-");
  AddAllowPartialFlag(cmd, &args->allow_partial);
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar and no summary");
  cmd->callback([args, exit_code] { *exit_code = RunRender(*args); });
}

}  // namespace meshvid::cli
