// `meshvid transcode`: a .mvid's displacement video coded again with another codec or quality,
// nothing else redone (codec/enc/coding/transcode.h). Its main use: AV1 for the web player.
#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "codec/common/progress.h"
#include "codec/dec/mvid_decoder.h"
#include "codec/enc/coding/transcode.h"
#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/terminal.h"

namespace meshvid::cli {
namespace {

struct TranscodeArguments {
  std::string input;
  std::string output;
  std::string codec{VideoCodecName(TranscodeOptions{}.codec)};  ///< --codec, AV1 by default
  TranscodeOptions options;
  bool quiet = false;
};

/// The input's metadata with a "transcoded" entry naming the codec it had and the quality it
/// was coded again at (a text that is not a JSON object is kept under "text").
std::string TranscodedMetadata(const std::string& metadata, std::string_view from_codec,
                               int quality) {
  nlohmann::json j =
      metadata.empty() ? nlohmann::json::object() : nlohmann::json::parse(metadata, nullptr, false);
  if (j.is_discarded() || !j.is_object()) j = {{"text", metadata}};
  j["transcoded"] = {{"from", std::string(from_codec)}, {"quality", quality}};
  return DumpJson(j);
}

int RunTranscode(TranscodeArguments& args) {
  const auto start = std::chrono::steady_clock::now();
  // --codec is checked by CLI11 against the names ParseVideoCodec knows.
  args.options.codec = ParseVideoCodec(args.codec).value_or(TranscodeOptions{}.codec);
  StatusOr<std::unique_ptr<MvidDecoder>> input = MvidDecoder::OpenFile(args.input);
  if (!input.ok()) return ReportError(input.status());
  const VideoCodec from = (*input)->info().codec;
  args.options.metadata_json = TranscodedMetadata((*input)->info().metadata_json,
                                                  VideoCodecName(from), args.options.quality);
  input->reset();

  ProgressBar bar(args.quiet);
  args.options.progress = bar.Callback();
  StatusOr<TranscodeSummary> summary = TranscodeVideo(args.input, args.output, args.options);
  bar.Finish();
  if (!summary.ok()) return ReportError(summary.status());
  if (!args.quiet) {
    const TranscodeSummary& s = *summary;
    std::fprintf(stderr,
                 "Transcoded %s (%s) into %s (%s, quality %d) in %.1f s: %s in %s\n"
                 "  video          %s -> %s\n"
                 "  file           %s -> %s (base meshes, motion and transforms copied)\n"
                 "  displacements  moved by %.3g RMS, %.3g at most (scene units)\n",
                 args.input.c_str(), std::string(VideoCodecName(from)).c_str(), args.output.c_str(),
                 args.codec.c_str(), args.options.quality, SecondsSince(start),
                 Count(s.frames, "frame").c_str(), Count(s.groups, "group").c_str(),
                 Kilobytes(double(s.input_video_bytes)).c_str(),
                 Kilobytes(double(s.output_video_bytes)).c_str(),
                 Kilobytes(double(s.input_bytes)).c_str(),
                 Kilobytes(double(s.output_bytes)).c_str(), s.displacement_rms_change,
                 s.displacement_max_change);
  }
  return 0;
}

}  // namespace

void AddTranscodeCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<TranscodeArguments>();
  CLI::App* cmd = app.add_subcommand(
      "transcode",
      "Code a .mvid's displacement video again with another codec or quality, nothing else\n"
      "redone: base meshes, motion and transforms are copied byte for byte, so it takes\n"
      "seconds where an encode takes minutes. AV1 is the codec browsers decode in 10 bits\n"
      "(WebCodecs), so `--codec av1` makes an HEVC or FFV1 file playable on the web. The\n"
      "pictures are decoded and coded again: from a lossy file the losses add up (the summary\n"
      "says how far the displacements moved); transcode from FFV1 (lossless) where you can.");
  cmd->add_option("FILE", args->input, "The .mvid to transcode")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output, "The transcoded .mvid")->required();
  cmd->add_option("--codec", args->codec, "Displacement video codec: av1, hevc or ffv1")
      ->capture_default_str()
      ->check(CLI::IsMember({"av1", "hevc", "ffv1"}));
  cmd->add_option("--quality", args->options.quality,
                  "0 (smallest) .. 100 (finest): the video quantiser as `meshvid encode` sets "
                  "it (the base and motion are copied as they are); FFV1 is lossless")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
  cmd->add_option("--effort", args->options.effort, "Video encoder effort 0 (fastest) .. 9")
      ->capture_default_str()
      ->check(CLI::Range(0, 9));
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar and no summary");
  cmd->callback([args, exit_code] { *exit_code = RunTranscode(*args); });
}

}  // namespace meshvid::cli
