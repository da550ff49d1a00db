// `meshvid simulate`: a multi-view range-camera capture of ground truth.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/option_checks.h"
#include "tools/cli/terminal.h"
#include "tools/io/file_pattern.h"
#include "tools/sim/ground_truth.h"
#include "tools/sim/simulator.h"

namespace meshvid::cli {
namespace {

/// Options as typed on the command line.
struct SimulateArgs {
  std::string ground_truth;
  std::string out_dir;
  int views = 3;
  std::string layout = "arc";
  std::string resolution = "640x480";
  double noise = 0.001;
  double dropout = 0.0;
  std::string frames;
  std::uint64_t seed = 1;
  double max_angle = 75.0;
  double depth_jump = 0.03;
  double arc_step = 40.0;
  double azimuth = 0.0;
  std::string up = "y";
  double fov = 0.0;
  double frame_rate = 25.0;
  bool no_colour = false;
  double exposure_spread = 0.1;
  double colour_noise = 2.0;
  bool quiet = false;
  std::string json;
};

/// Parses "WxH" into the rig's image size.
Status ParseResolution(const std::string& text, RigOptions* rig) {
  int width = 0, height = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 ||
      (x != 'x' && x != 'X') || width < 2 || height < 2 || width > 16384 || height > 16384) {
    return InvalidArgumentError("--res '" + text +
                                "' is not a valid image size: use WIDTHxHEIGHT, e.g. 640x480, "
                                "each between 2 and 16384");
  }
  rig->width = width;
  rig->height = height;
  return Status::Ok();
}

/// Turns the command-line options into SimulateOptions (usage errors only).
Status BuildOptions(const SimulateArgs& args, SimulateOptions* options) {
  if (args.views < 1) {
    return InvalidArgumentError("--views must be at least 1 (got " +
                                std::to_string(args.views) + ")");
  }
  if (!(args.dropout >= 0 && args.dropout < 1)) {
    return InvalidArgumentError("--dropout is a probability in [0, 1) (got " +
                                std::to_string(args.dropout) + ")");
  }
  MESHVID_RETURN_IF_ERROR(ParseResolution(args.resolution, &options->rig));
  options->rig.views = args.views;
  options->rig.layout = args.layout == "ring" ? RigLayout::kRing : RigLayout::kArc;
  options->rig.arc_step_deg = args.arc_step;
  options->rig.azimuth_deg = args.azimuth;
  options->rig.up = args.up == "z" ? UpAxis::kZ : UpAxis::kY;
  options->rig.fov_deg = args.fov;
  options->sensor.noise_sigma = args.noise;
  options->sensor.dropout = args.dropout;
  options->sensor.seed = args.seed;
  options->sensor.max_angle_deg = args.max_angle;
  options->sensor.meshing.max_depth_jump_ratio = static_cast<float>(args.depth_jump);
  options->sensor.exposure_spread = args.exposure_spread;
  options->sensor.colour_noise = args.colour_noise;
  options->colour = !args.no_colour;
  options->ground_truth_spec = args.ground_truth;
  return ValidateSensorOptions(options->sensor);
}

std::string HumanBytes(long long bytes) {
  char text[32];
  if (bytes >= 1'000'000) {
    std::snprintf(text, sizeof(text), "%.1f MB", bytes / 1e6);
  } else {
    std::snprintf(text, sizeof(text), "%.1f kB", bytes / 1e3);
  }
  return text;
}

/// "+z", "-y", or the components: the direction the rig looks from.
std::string DirectionText(const Eigen::Vector3d& d) {
  static const char* const kAxes[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    if (std::abs(std::abs(d[a]) - 1.0) < 1e-6)
      return (d[a] > 0 ? "+" : "-") + std::string(kAxes[a]);
  }
  char text[64];
  std::snprintf(text, sizeof(text), "(%.2f, %.2f, %.2f)", d.x(), d.y(), d.z());
  return text;
}

/// Where the cameras look from, and a hint when the subject looks side-on from there (a
/// person is wider across the shoulders than deep).
std::string FacingText(const SimulateSummary& s, const SimulateArgs& args) {
  char text[400];
  std::snprintf(text, sizeof(text),
                "The rig's centre looks at the subject from %s (azimuth %g deg about +%s; "
                "--azimuth turns it)",
                DirectionText(s.rig_direction).c_str(), args.azimuth, args.up.c_str());
  std::string out = text;
  constexpr double kSideOnRatio = 1.2;
  if (s.depth_over_width > kSideOnRatio) {
    std::snprintf(text, sizeof(text),
                  ". Seen from there the subject is %.1fx deeper than wide: it may be side-on "
                  "to the cameras (--azimuth 90 or -90 would face its wide side).",
                  s.depth_over_width);
    out += text;
  } else {
    out += ".";
  }
  return out;
}

/// Where the colour came from and how the views see it.
std::string ColourText(const SimulateSummary& s, const SimulateOptions& options) {
  switch (s.colour_source) {
    case ColourSource::kNone:
      return options.colour ? "No colour: the ground truth has no vertex colours of its own and "
                              "changes connectivity, so no albedo can ride its surface."
                            : "No colour (--no-colour).";
    case ColourSource::kGroundTruth:
    case ColourSource::kAlbedo:
      break;
  }
  std::string gains;
  for (double gain : s.exposure_gains) {
    char text[16];
    std::snprintf(text, sizeof(text), "%s%.2f", gains.empty() ? "" : " ", gain);
    gains += text;
  }
  char noise[32];
  std::snprintf(noise, sizeof(noise), "%g", options.sensor.colour_noise);
  return std::string("Colour: ") +
         (s.colour_source == ColourSource::kAlbedo ? "a procedural albedo fixed to the surface"
                                                   : "the ground truth's own vertex colours") +
         ", seen with exposure gains " + gains + " and noise " + noise + ".";
}

int RunSimulate(const SimulateArgs& args) {
  SimulateOptions options;
  if (Status status = BuildOptions(args, &options); !status.ok()) {
    ReportError(status);
    return 2;
  }
  StatusOr<std::unique_ptr<MeshSequence>> ground_truth =
      OpenGroundTruth(args.ground_truth, args.frame_rate);
  if (!ground_truth.ok()) return ReportError(ground_truth.status());
  MeshSequence& sequence = **ground_truth;
  if (!args.frames.empty()) {
    StatusOr<std::pair<int, int>> range = FramesOption(args.frames, sequence.frame_count());
    if (!range.ok()) {
      ReportError(range.status());
      return 2;
    }
    options.first_frame = range->first;
    options.end_frame = range->second;
  }
  ProgressBar bar(args.quiet);
  StatusOr<SimulateSummary> summary =
      SimulateCapture(sequence, args.out_dir, options, bar.Callback());
  bar.Finish();
  if (!summary.ok()) return ReportError(summary.status());
  if (!args.json.empty()) {
    const SimulateSummary& s = *summary;
    const nlohmann::json j = {
        {"manifest", ToValidUtf8(s.manifest_path)},
        {"frames", s.frames},
        {"views", s.views},
        {"pixels", s.pixels},
        {"hit_pixels", s.hit_pixels},
        {"samples", s.samples},
        {"output_bytes", s.output_bytes},
        {"seconds", s.seconds},
        {"rig_direction", {s.rig_direction.x(), s.rig_direction.y(), s.rig_direction.z()}},
        {"depth_over_width", s.depth_over_width},
        {"colour", ColourSourceName(s.colour_source)},
        {"exposure_gains", s.exposure_gains}};
    const Status written = WriteJsonOutput(args.json, DumpJson(j, 2) + "\n");
    if (!written.ok()) return ReportError(written);
  }
  if (!args.quiet) {
    const SimulateSummary& s = *summary;
    const double view_frames = static_cast<double>(s.frames) * s.views;
    std::fprintf(
        stderr,
        "Simulated %s x %s (%dx%d, %s layout) of %s into %s: on average %.0f "
        "samples per view and frame, %.1f%% of pixels hit the subject and %.1f%% were kept "
        "(noise %g, grazing limit %g deg, drop-out %g); %s written in %.2f s (%.1f frames/s). "
        "Open it with %s.\n",
        Count(s.frames, "frame").c_str(), Count(s.views, "view").c_str(), options.rig.width,
        options.rig.height, options.rig.layout == RigLayout::kArc ? "arc" : "ring",
        sequence.description().c_str(), args.out_dir.c_str(), s.samples / view_frames,
        s.pixels > 0 ? 100.0 * s.hit_pixels / s.pixels : 0.0,
        s.pixels > 0 ? 100.0 * s.samples / s.pixels : 0.0, options.sensor.noise_sigma,
        options.sensor.max_angle_deg, options.sensor.dropout, HumanBytes(s.output_bytes).c_str(),
        s.seconds, s.seconds > 0 ? s.frames / s.seconds : 0.0, s.manifest_path.c_str());
    std::fprintf(stderr, "%s\n", FacingText(s, args).c_str());
    std::fprintf(stderr, "%s\n", ColourText(s, options).c_str());
  }
  return 0;
}

}  // namespace

void AddSimulateCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Simulate a multi-view range-camera capture of ground truth: K pinhole range cameras\n"
      "ray-cast every frame, with noise, grazing-angle loss and drop-outs; writes one range\n"
      "mesh per view per frame, manifest.json and the ground truth of the simulated frames.");
  cmd->add_option("GT", args->ground_truth,
                  "Ground truth: NAME.obj with NAME.pc2 beside it, a folder of per-frame "
                  "meshes, a {frame} pattern, or scene:arm-block / scene:cloth")
      ->required();
  cmd->add_option("-o,--out", args->out_dir, "Output folder (created if missing)")->required();
  cmd->add_option("--views", args->views, "Number of range cameras K")->capture_default_str();
  cmd->add_option("--layout", args->layout,
                  "arc: frontal arc, --arc-step degrees apart; ring: evenly over 360 degrees")
      ->check(CLI::IsMember({"arc", "ring"}))
      ->capture_default_str();
  cmd->add_option("--res", args->resolution, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--noise", args->noise,
                  "Std. deviation of the Gaussian noise along each ray, in ground-truth units")
      ->capture_default_str();
  cmd->add_option("--dropout", args->dropout, "Probability that a sample is lost, in [0, 1)")
      ->capture_default_str();
  cmd->add_option("--frames", args->frames,
                  "Ground-truth frames A:B (half-open; A:, :B or N) -> capture frames 0..B-A-1")
      ->type_name("A:B");
  cmd->add_option("--seed", args->seed, "Seed of the noise and drop-outs")->capture_default_str();
  cmd->add_option("--max-angle", args->max_angle,
                  "Samples seen at more than this angle (degrees) from the normal are lost")
      ->capture_default_str();
  cmd->add_option("--depth-jump", args->depth_jump,
                  "Meshing: drop triangles whose depth range exceeds this ratio of their depth")
      ->capture_default_str();
  cmd->add_option("--arc-step", args->arc_step, "Degrees between views of the arc layout")
      ->capture_default_str();
  cmd->add_option("--azimuth", args->azimuth,
                  "Turn the whole rig by this many degrees about the up axis (0: centred on\n"
                  "the front; samba's dancer faces +x: use 90; the summary says when a\n"
                  "subject looks side-on)")
      ->capture_default_str();
  cmd->add_option("--up", args->up, "Up axis of the data (front is +z for y, -y for z)")
      ->check(CLI::IsMember({"y", "z"}))
      ->capture_default_str();
  cmd->add_option("--fov", args->fov,
                  "Horizontal field of view in degrees (default: Kinect-like, fx = 525 at 640)");
  cmd->add_option("--fps", args->frame_rate,
                  "Frame rate for ground truth that does not store one")
      ->capture_default_str();
  cmd->add_flag("--no-colour", args->no_colour,
                "No colour. By default the views and the written ground truth carry colour:\n"
                "the ground truth's own vertex colours, or else a procedural albedo fixed to\n"
                "its surface (ground truth of fixed connectivity)");
  cmd->add_option("--exposure-spread", args->exposure_spread,
                  "Each view scales colour by its own exposure gain exp(spread * N(0, 1)),\n"
                  "drawn once per view; 0: every view sees the same colour")
      ->capture_default_str();
  cmd->add_option("--colour-noise", args->colour_noise,
                  "Std. deviation of each colour sample's noise, in 8-bit units")
      ->capture_default_str();
  cmd->add_option("--json", args->json, JsonOptionHelp("Also write the summary"))
      ->type_name("FILE|-");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar and no summary");
  cmd->callback([args, exit_code] { *exit_code = RunSimulate(*args); });
}

}  // namespace meshvid::cli
