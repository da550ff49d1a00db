// `meshvid encode`: a multi-view capture to a .mvid (base mesh, rigid motion, displacement video).
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/common/progress.h"
#include "codec/enc/encoder.h"
#include "format/output_file.h"
#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/option_checks.h"
#include "tools/cli/terminal.h"
#include "tools/io/capture_frame_source.h"
#include "tools/io/file_pattern.h"
#include "tools/io/mesh_io.h"

namespace meshvid::cli {
namespace {

struct EncodeArguments {
  std::string capture;
  std::string output;
  std::string base_mesh;
  std::string codec{VideoCodecName(EncoderOptions{}.codec)};  ///< --codec, the encoder's default
  std::string frames;
  std::string summary_json;
  std::vector<std::string> tune;  ///< --tune: KEY=VALUE or FILE.json entries, in order
  bool quiet = false;
  EncoderOptions options;
};

/// The encoder's messages name EncoderOptions' fields ("levels must be in 0..4"); the command
/// line's user knows them by their flags. Field names with an underscore become their flag
/// wherever they occur; plain words (quality, levels, ...) only as the message's first. The
/// internals (tuning.KEY) are set with `--tune KEY=VALUE`.
Status WithFlagNames(const Status& status) {
  static constexpr std::pair<std::string_view, std::string_view> kFlags[] = {
      {"quality", "--quality"},
      {"levels", "--levels"},
      {"effort", "--effort"},
      {"gof_size", "--gof"},
      {"rebase_gain_db", "--rebase-gain"},
      {"max_key_groups", "--max-key-groups"},
      {"base_vertices", "--base-vertices"},
  };
  if (status.code() != StatusCode::kInvalidArgument) return status;
  std::string in = status.message();
  // "tuning.KEY" (not "docs/tuning.md") becomes "--tune KEY".
  for (std::size_t at = 0; (at = in.find("tuning.", at)) != std::string::npos;) {
    if (at > 0 && in[at - 1] != ' ' && in[at - 1] != '(') {
      at += 7;
      continue;
    }
    in.replace(at, 7, "--tune ");
  }
  const auto is_word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  std::string out;
  for (std::size_t i = 0; i < in.size();) {
    std::size_t end = i;
    while (end < in.size() && is_word(in[end])) ++end;
    if (end == i) {
      out += in[i++];
      continue;
    }
    const std::string_view word(in.data() + i, end - i);
    std::string_view replacement = word;
    const bool identifier = word.find('_') != std::string_view::npos;
    for (const auto& [field, flag] : kFlags) {
      if (word == field && (identifier || i == 0)) replacement = flag;
    }
    out += replacement;
    i = end;
  }
  return {status.code(), out};
}

/// The knobs as `--tune help` prints them: key, default, range, then what each does.
std::string TuningHelp() {
  const EncoderTuning defaults;
  std::string text =
      "The encoder's internals, set with --tune KEY=VALUE (or a JSON file of them). Lengths\n"
      "are in scene units; 0 derives a length from frame 0's size. Every default was chosen by\n"
      "measurement (bench/); change them to experiment, not to use the codec.\n\n";
  for (const TuningKnob& knob : TuningKnobs()) {
    text += std::string("  ") + knob.key + " = " + TuningValue(defaults, knob.key) + "  (" +
            knob.type + ", " + TuningRangeText(knob) + ")\n";
    // The help, wrapped at 90 columns under the key.
    std::string line = "     ";
    std::istringstream words(knob.help);
    for (std::string word; words >> word;) {
      if (line.size() + 1 + word.size() > 90) {
        text += line + "\n";
        line = "     ";
      }
      line += " " + word;
    }
    text += line + "\n";
  }
  return text;
}

/// Applies the --tune entries in order: KEY=VALUE, or a JSON file holding an object of them.
Status ApplyTune(const std::vector<std::string>& entries, EncoderTuning& tuning) {
  for (const std::string& entry : entries) {
    const std::size_t equals = entry.find('=');
    if (equals != std::string::npos) {
      const Status set = SetTuning(tuning, entry.substr(0, equals), entry.substr(equals + 1));
      if (!set.ok()) return WithFlagNames(set);
      continue;
    }
    std::ifstream file(entry);
    if (!file) {
      return InvalidArgumentError("--tune: '" + entry +
                                  "' is neither KEY=VALUE nor a readable JSON file");
    }
    const nlohmann::json object = nlohmann::json::parse(file, nullptr, /*allow_exceptions=*/false);
    if (!object.is_object()) {
      return InvalidArgumentError("--tune " + entry + ": not a JSON object of KEY: VALUE");
    }
    for (const auto& [key, value] : object.items()) {
      if (!value.is_number() && !value.is_boolean() && !value.is_string()) {
        return InvalidArgumentError("--tune " + entry + ": " + key +
                                    " must be a number or true/false");
      }
      const std::string text = value.is_string() ? value.get<std::string>() : value.dump();
      const Status set = SetTuning(tuning, key, text);
      if (!set.ok()) return WithFlagNames(set).WithContext("--tune " + entry);
    }
  }
  return Status::Ok();
}

/// The file's rate at the capture's frame rate.
double MbitPerSecond(const EncodeSummary& s) {
  return double(s.stats.total_bytes) * 8.0 / std::max(1, s.frames) * s.frame_rate / 1e6;
}

nlohmann::json SummaryJson(const EncodeSummary& s, const EncodeArguments& args, double seconds) {
  const double frames = std::max(1, s.frames);
  nlohmann::json j;
  j["capture"] = args.capture;
  j["output"] = args.output;
  j["codec"] = args.codec;
  j["quality"] = args.options.quality;
  j["qp"] = QualityToQp(args.options.codec, args.options.quality);
  j["levels"] = args.options.levels;
  j["frames"] = s.frames;
  j["views"] = s.views;
  j["free_space_views"] = s.free_space_views;
  j["frame_rate"] = s.frame_rate;
  j["base_vertices"] = s.base_vertices;
  j["samples_per_frame"] = s.samples_per_frame;
  j["segments"] = s.segments;
  j["surface_share"] = s.surface_share;
  j["filled_share"] = s.filled_share;
  j["hit_share"] = s.hit_share;
  j["key_groups"] = nlohmann::json::array();
  for (const KeyGroupSummary& k : s.key_groups) {
    nlohmann::json held = nlohmann::json::array();
    for (const HeldFrame& h : k.held_frames) {
      held.push_back({{"frame", h.frame},
                      {"loss_db", h.loss_db},
                      {"unexplained", h.unexplained_share},
                      {"seen_through", h.seen_through_share}});
    }
    j["key_groups"].push_back({{"first_frame", k.first_frame},
                               {"key_frame", k.key_frame},
                               {"frames", k.frames},
                               {"base_vertices", k.base_vertices},
                               {"segments", k.segments},
                               {"rigid_groups", k.rigid_groups},
                               {"reacquired_parts", k.reacquired_parts},
                               {"surface_share", k.surface_share},
                               {"key_frame_unexplained", k.key_frame_unexplained},
                               {"key_frame_seen_through", k.key_frame_seen_through},
                               {"worst_unexplained", k.worst_unexplained},
                               {"worst_loss_db", k.worst_loss_db},
                               {"cut_loss_db", k.cut_loss_db},
                               {"cut_unexplained", k.cut_unexplained},
                               {"cut_seen_through", k.cut_seen_through},
                               {"cut_farthest_growth", k.cut_farthest_growth},
                               {"held_frames", held}});
  }
  j["scale"] = s.scale;
  j["tolerance"] = s.tolerance;
  j["bytes_total"] = s.stats.total_bytes;
  j["bytes_base"] = s.stats.base_bytes;
  j["bytes_motion"] = s.stats.motion_bytes;
  j["bytes_transforms"] = s.stats.transform_bytes;
  j["bytes_video"] = s.stats.video_bytes;
  j["bytes_colour"] = s.stats.colour_bytes;
  j["bytes_per_frame"] = double(s.stats.total_bytes) / frames;
  j["mbit_per_s"] = MbitPerSecond(s);
  j["seconds"] = seconds;
  j["frames_per_second"] = seconds > 0 ? frames / seconds : 0.0;
  j["seconds_by_stage"] = {{"base", s.seconds_base},
                           {"tracking", s.seconds_tracking},
                           {"detail", s.seconds_detail},
                           {"coding", s.seconds_coding}};
  return j;
}

/// The summary's line on the motion, counting segments as `meshvid info` does (key group 0's,
/// as stored in the file): the deformation's nodes and the rigid groups they were joined
/// into; then the means over the key groups.
std::string MotionLine(const EncodeSummary& s) {
  const KeyGroupSummary first = s.key_groups.empty() ? KeyGroupSummary() : s.key_groups.front();
  char line[320];
  std::snprintf(line, sizeof(line),
                "  motion        %s (deformation nodes) moving as %s in key group 0; "
                "means over key groups %d and %d; %.1f%% of base triangles seen\n",
                Count(first.segments, "segment").c_str(),
                Count(first.rigid_groups, "rigid group").c_str(), s.segments, s.rigid_groups,
                100 * s.surface_share);
  return line;
}

/// Says which frames a key group kept although its base did not explain them (held by
/// --max-key-groups), and by how much: the encode is quietly worse there otherwise.
void PrintHeldFrames(const EncodeSummary& s, const EncoderOptions& options) {
  for (std::size_t k = 0; k < s.key_groups.size(); ++k) {
    const std::vector<HeldFrame>& held = s.key_groups[k].held_frames;
    if (held.empty()) continue;
    const HeldFrame worst = *std::max_element(
        held.begin(), held.end(),
        [](const HeldFrame& a, const HeldFrame& b) { return a.loss_db < b.loss_db; });
    std::fprintf(stderr,
                 "  warning       --max-key-groups %d: key group %zu keeps %s its base does not "
                 "explain (from frame %d; a fresh base would gain up to %.1f dB, at frame %d, "
                 "where %.1f%% of the points are out of reach); allow more key groups there\n",
                 options.max_key_groups, k, Count(held.size(), "frame").c_str(), held.front().frame,
                 worst.loss_db, worst.frame, 100 * worst.unexplained_share);
  }
}

void PrintSummary(const EncodeSummary& s, const EncodeArguments& args, double seconds) {
  const double frames = std::max(1, s.frames);
  const MvidWriteStats& b = s.stats;
  std::fprintf(stderr,
               "Encoded %s x %s of %s into %s in %.1f s (%.2f frames/s)\n"
               "  key groups    %zu (mean %.1f frames; a fresh base where it gains more D1 than "
               "its bytes are worth)\n"
               "  base mesh     %zu vertices, %zu displacement samples per frame (level %d)\n"
               "%s"
               "  detail        %.1f%% of samples measured, %.1f%% filled by interpolation\n"
               "  bytes         base %s, motion %s, transforms %s, video %s%s, total %s\n"
               "  rate          %s per frame, %.3f Mbit/s at %.3g frames/s\n",
               Count(s.frames, "frame").c_str(), Count(s.views, "view").c_str(),
               args.capture.c_str(), args.output.c_str(), seconds, frames / seconds,
               s.key_groups.size(), frames / double(std::max<std::size_t>(1, s.key_groups.size())),
               s.base_vertices, s.samples_per_frame, args.options.levels, MotionLine(s).c_str(),
               100 * s.hit_share, 100 * s.filled_share, Kilobytes(b.base_bytes).c_str(),
               Kilobytes(b.motion_bytes).c_str(), Kilobytes(b.transform_bytes).c_str(),
               Kilobytes(b.video_bytes).c_str(),
               b.colour_bytes > 0 ? (", colour " + Kilobytes(b.colour_bytes)).c_str() : "",
               Kilobytes(b.total_bytes).c_str(),
               Kilobytes(b.total_bytes / frames).c_str(), MbitPerSecond(s), s.frame_rate);
  PrintHeldFrames(s, args.options);
  if (s.free_space_views > 0) {
    std::fprintf(stderr,
                 "  free space    %d of %d views calibrated: bases end, and key groups end, "
                 "where a camera saw through the surface\n",
                 s.free_space_views, s.views);
  }
}

int RunEncode(EncodeArguments args) {
  if (const Status tuned = ApplyTune(args.tune, args.options.tuning); !tuned.ok()) {
    return ReportError(tuned);
  }
  const std::optional<VideoCodec> codec = ParseVideoCodec(args.codec);
  if (!codec) {
    return ReportError(InvalidArgumentError("--codec: unknown codec '" + args.codec +
                                            "' (hevc, av1 or ffv1)"));
  }
  args.options.codec = *codec;
  StatusOr<std::unique_ptr<CaptureFrameSource>> source =
      CaptureFrameSource::Open(args.capture);
  if (!source.ok()) return ReportError(source.status());
  if (!args.frames.empty()) {
    StatusOr<std::pair<int, int>> range = FramesOption(args.frames, (*source)->frame_count());
    if (!range.ok()) return ReportError(range.status());
    args.options.first_frame = range->first;
    args.options.end_frame = range->second;
  }
  // Only the frames encoded need their files (a capture may be encoded in pieces).
  const Status files = (*source)->capture().CheckViewFiles(
      args.options.first_frame,
      args.options.end_frame < 0 ? (*source)->frame_count() : args.options.end_frame);
  if (!files.ok()) return ReportError(files);
  if (!args.base_mesh.empty()) {
    StatusOr<TriangleMesh> base = ReadMesh(args.base_mesh);
    if (!base.ok()) return ReportError(base.status().WithContext("--base-mesh"));
    args.options.base_mesh = std::move(*base);
  }
  nlohmann::json metadata;
  metadata["encoder"] = "meshvid encode";
  metadata["capture"] = std::filesystem::path(args.capture).filename().string();
  // The capture frames the file holds, so that `meshvid concat` can check that pieces follow
  // each other.
  metadata["capture_frames"] = {args.options.first_frame, args.options.end_frame < 0
                                                              ? (*source)->frame_count()
                                                              : args.options.end_frame};
  args.options.metadata_json = DumpJson(metadata);  // the file name may not be UTF-8

  // Written to a temporary file first: a failed encode never leaves a truncated .mvid behind,
  // and a bad output path fails before any work.
  StatusOr<std::unique_ptr<OutputFile>> out = OutputFile::Open(args.output);
  if (!out.ok()) return ReportError(out.status().WithContext("-o"));
  ProgressBar bar(args.quiet);
  const auto start = std::chrono::steady_clock::now();
  StatusOr<EncodeSummary> summary = EncodeCapture(
      **source, OstreamSink((*out)->stream(), args.output), args.options, bar.Callback());
  bar.Finish();
  if (!summary.ok()) return ReportError(WithFlagNames(summary.status()));
  const Status committed = (*out)->Commit();
  if (!committed.ok()) return ReportError(committed);
  const double seconds = SecondsSince(start);
  if (!args.quiet) PrintSummary(*summary, args, seconds);
  if (!args.summary_json.empty()) {
    const Status written = WriteJsonOutput(
        args.summary_json, DumpJson(SummaryJson(*summary, args, seconds), 2) + "\n");
    if (!written.ok()) return ReportError(written.WithContext("--summary-json"));
  }
  return 0;
}

}  // namespace

std::string FormerTuningFlagHint(const std::vector<std::string>& args) {
  std::string hint;
  for (const std::string& arg : args) {
    for (const TuningKnob& knob : TuningKnobs()) {
      if (arg == knob.former_flag) {
        hint +=
            std::string(hint.empty() ? "" : "; ") + arg + " is now --tune " + knob.key + "=VALUE";
      }
    }
  }
  return hint;
}

void AddEncodeCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<EncodeArguments>();
  EncoderOptions& o = args->options;
  CLI::App* cmd = app.add_subcommand(
      "encode",
      "Encode a multi-view capture into a .mvid: per key group a base mesh (fused from its\n"
      "first frame or given), its motion (an embedded deformation tracked frame by frame),\n"
      "and the fused surface detail as a displacement video. Lengths default to fractions of\n"
      "frame 0's size.");
  cmd->add_option("CAPTURE", args->capture,
                  "The capture: a manifest.json, a file pattern with {frame} and {view} "
                  "(cap/f{frame:04}_v{view}.ply) or a Stanford .conf")
      ->required();
  cmd->add_option("-o,--out", args->output, "The .mvid file to write")->required();
  cmd->add_option("--frames", args->frames, "Frame range A:B (half-open), A:, :B or N")
      ->type_name("A:B");
  cmd->add_option(
         "--codec", args->codec,
         "Displacement video codec: av1 (the default: the smallest files, and the one browsers "
         "decode), hevc or ffv1 (lossless)")
      ->capture_default_str();
  cmd->add_option("--quality", o.quality,
                  "0 (smallest) .. 100 (finest); sets the video quantiser (AV1 CRF = "
                  "63 x (1 - q/100), HEVC QP = 51 x (1 - q/100); FFV1 is lossless) and the "
                  "--rebase-gain; below 30 also a coarser base mesh and motion (half the base's "
                  "vertices, twice the transform step and 1.41x the motion's node spacing every "
                  "15 steps down)")
      ->capture_default_str();
  cmd->add_option("--colour-quality", o.colour_quality,
                  "Quality of the colour video, as --quality (default: --quality's). A capture "
                  "whose views all have vertex colours is coded with a colour stream")
      ->type_name("Q");
  cmd->add_flag("--no-colour{false}", o.colour, "Geometry only, even if the capture has colour");
  cmd->add_option("--levels", o.levels,
                  "Subdivision levels of the displacement lattice: the finest resolution a "
                  "decoder can choose")
      ->capture_default_str();
  cmd->add_option("--effort", o.effort, "Video encoder effort 0 (fastest) .. 9")
      ->capture_default_str();
  cmd->add_option("--gof", o.gof_size, "Frames per group (random-access unit)")
      ->capture_default_str();
  cmd->add_option(
         "--rebase-gain", o.rebase_gain_db,
         "Start a new key group (a fresh base fused from that frame) only where it is "
         "estimated to gain more than this D1, in dB, over the tracked base: from the "
         "captured points the tracked base's displacements cannot reach and its "
         "surface lying where a camera saw through (--tune seen_free_space). Given at quality "
         "40; doubled every 20 quality steps below, halved every 20 above up to 80. Smaller: "
         "more key groups, closer to per-frame fusion; 0: a new key group wherever "
         "tracking loses anything")
      ->capture_default_str();
  cmd->add_option("--max-key-groups", o.max_key_groups,
                  "Most key groups; 1 keeps one base and one connectivity for the whole "
                  "capture (for editing), 0: no limit")
      ->capture_default_str();
  // Triggered on each occurrence (so that `--tune help` prints before the required arguments
  // are checked), which clears the option's results each time: the entries are collected here.
  cmd->add_option("--tune",
                  "Set an internal of the encoder: KEY=VALUE, or a JSON file of them "
                  "({\"node_spacing\": 0.03}); repeatable, later ones win. `--tune help` "
                  "lists every key with its default and range (docs/tuning.md)")
      ->type_name("KEY=VALUE|FILE.json|help")
      ->expected(1)
      ->take_all()
      ->trigger_on_parse()
      ->each([args](const std::string& entry) {
        if (entry != "help") {
          args->tune.push_back(entry);
          return;
        }
        std::fputs(TuningHelp().c_str(), stdout);
        throw CLI::Success();
      });
  cmd->add_option("--base-mesh", args->base_mesh,
                  "Use this mesh (PLY/OBJ) as the base, rigidly fitted to each key group's "
                  "first frame, instead of fusing that frame's views");
  cmd->add_option("--base-vertices", o.base_vertices,
                  "Vertices of the automatic base mesh after decimation, at quality 30 and "
                  "above (a target: the decimation's bounds may stop it sooner); halved every "
                  "15 quality steps below")
      ->capture_default_str();
  cmd->add_flag("--hide-unseen", o.hide_unseen,
                "Leave out of the decoded surface the base triangles no view saw in any frame "
                "(default: decode the whole base surface, unseen parts moved and filled)");
  cmd->add_option("--json,--summary-json", args->summary_json,
                  JsonOptionHelp("Also write the summary (bytes per stream, rate, timings, "
                                 "key groups)"))
      ->type_name("FILE|-");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar and no summary");
  cmd->callback([args, exit_code] { *exit_code = RunEncode(*args); });
}

}  // namespace meshvid::cli
