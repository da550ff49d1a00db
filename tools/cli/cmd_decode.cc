// `meshvid decode`: a .mvid to one mesh file per frame, at a chosen level; or, with
// --no-write, every frame decoded and timed without writing (decoder speed).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "codec/dec/mvid_decoder.h"
#include "format/container_reader.h"
#include "format/output_file.h"
#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/option_checks.h"
#include "tools/cli/terminal.h"
#include "tools/io/file_pattern.h"
#include "tools/io/mesh_io.h"

namespace meshvid::cli {
namespace {

struct DecodeArguments {
  std::string file;
  std::string output;
  int level = -1;
  std::string frames;
  std::string json;
  bool ascii = false;
  bool no_write = false;
  bool quiet = false;
};

/// Writes the timing of a decode as JSON (for meshvid bench and scripts).
Status WriteDecodeJson(const DecodeArguments& args, int level, std::uint64_t frames,
                       double open_seconds, double seconds, const MvidInfo& info) {
  const nlohmann::json j = {{"file", args.file},
                            {"level", level},
                            {"frames", frames},
                            {"written", !args.no_write},
                            {"open_seconds", open_seconds},
                            {"seconds", seconds},
                            {"frames_per_second", seconds > 0 ? double(frames) / seconds : 0.0},
                            {"vertices", info.vertices_per_level[level]},
                            {"triangles", info.triangles_per_level[level]}};
  return WriteFileAtomically(args.json, DumpJson(j, 2) + "\n");
}

/// Checks the frames the decoder can read against those the file's header promises (0:
/// unknown): an error if there are none, a warning on stderr if they differ.
Status CheckReadableFrames(const std::string& file, std::uint32_t readable) {
  StatusOr<ContainerReader> reader = ContainerReader::OpenFile(file);
  const std::uint32_t promised = reader.ok() ? reader->header().frame_count : 0;
  const std::string promise =
      promised > 0 ? "the header promises " + std::to_string(promised) + " frames" : "";
  if (readable == 0) {
    return CorruptError(file + ": no frame is readable (" +
                        (promised > 0 ? promise + "; the" : "the") +
                        " file is cut or damaged in its first group of frames)");
  }
  if (promised > 0 && readable < promised) {
    std::fprintf(stderr,
                 "meshvid: warning: %s: only %u of the %u frames the header promises are "
                 "readable (the file is cut or damaged); decoding frames 0..%u at most\n",
                 file.c_str(), readable, promised, readable - 1);
  } else if (promised > 0 && readable > promised) {
    std::fprintf(stderr,
                 "meshvid: warning: %s: its groups hold %u frames, %s (the file is damaged)\n",
                 file.c_str(), readable, promise.c_str());
  }
  return Status::Ok();
}

int RunDecode(const DecodeArguments& args) {
  if (args.no_write == !args.output.empty()) {
    std::fprintf(stderr, "meshvid: decode needs either -o PATTERN or --no-write (not both)\n");
    return 2;
  }
  StatusOr<FilePattern> pattern = FilePattern::Parse(args.no_write ? "{frame}" : args.output);
  if (!pattern.ok()) return ReportError(pattern.status().WithContext("-o"));
  if (!pattern->has_frame() || pattern->has_view()) {
    std::fprintf(stderr,
                 "meshvid: -o needs a {frame} placeholder and no {view}, e.g. "
                 "out/f{frame:04}.ply\n");
    return 2;
  }
  using Clock = std::chrono::steady_clock;
  const Clock::time_point open_start = Clock::now();
  StatusOr<std::unique_ptr<MvidDecoder>> decoder = MvidDecoder::OpenFile(args.file);
  if (!decoder.ok()) return ReportError(decoder.status());
  const MvidInfo& info = (*decoder)->info();
  const int level = args.level < 0 ? info.levels : args.level;
  if (level > info.levels) {
    return ReportError(InvalidArgumentError(args.file + " stores levels 0.." +
                                            std::to_string(info.levels) + ", not " +
                                            std::to_string(level)));
  }
  const Status frames_checked = CheckReadableFrames(args.file, info.frame_count);
  if (!frames_checked.ok()) return ReportError(frames_checked);
  // Frame numbers are u32; --frames (int) can address the first 2^31 - 1 of them.
  std::uint32_t first = 0, end = info.frame_count;
  if (!args.frames.empty()) {
    const int addressable = static_cast<int>(
        std::min<std::uint32_t>(end, std::numeric_limits<int>::max()));
    StatusOr<std::pair<int, int>> range = ParseFrameRange(args.frames, addressable);
    if (!range.ok()) return ReportError(range.status().WithContext("--frames"));
    first = static_cast<std::uint32_t>(range->first);
    end = static_cast<std::uint32_t>(range->second);
  }
  MeshWriteOptions write_options;
  write_options.ply_encoding = args.ascii ? PlyEncoding::kAscii : PlyEncoding::kBinaryLittleEndian;
  ProgressBar bar(args.quiet);
  const ProgressCallback progress = bar.Callback();
  const Clock::time_point start = Clock::now();
  const double open_seconds = std::chrono::duration<double>(start - open_start).count();
  for (std::uint32_t frame = first; frame < end; ++frame) {
    StatusOr<TriangleMesh> mesh = (*decoder)->DecodeFrame(frame, level);
    if (!mesh.ok()) return ReportError(mesh.status());
    if (!args.no_write) {
      const std::string path = pattern->Expand(frame);
      const Status written = WriteMesh(path, *mesh, write_options);
      if (!written.ok()) return ReportError(written);
    }
    ReportProgress(progress, "decoding", static_cast<long>(frame - first) + 1,
                   static_cast<long>(end - first));
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  bar.Finish();
  if (!args.json.empty()) {
    const Status written = WriteDecodeJson(args, level, end - first, open_seconds, seconds, info);
    if (!written.ok()) return ReportError(written);
  }
  if (!args.quiet && args.no_write) {
    std::fprintf(stderr,
                 "Decoded frames %u..%u of %s at level %d (%zu vertices, %zu triangles "
                 "each) in %.3f s: %.1f frames/s, nothing written\n",
                 first, end - 1, args.file.c_str(), level, info.vertices_per_level[level],
                 info.triangles_per_level[level], seconds,
                 seconds > 0 ? (end - first) / seconds : 0.0);
  } else if (!args.quiet) {
    std::fprintf(stderr,
                 "Decoded frames %u..%u of %s at level %d (%zu vertices, %zu triangles "
                 "each) to %s\n",
                 first, end - 1, args.file.c_str(), level, info.vertices_per_level[level],
                 info.triangles_per_level[level], args.output.c_str());
  }
  return 0;
}

}  // namespace

void AddDecodeCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<DecodeArguments>();
  CLI::App* cmd = app.add_subcommand(
      "decode",
      "Decode a .mvid into one mesh file per frame (binary PLY, ascii PLY or OBJ by the\n"
      "pattern's extension). Every frame of a level has the same triangles. With --no-write,\n"
      "decode every frame without writing it and report the decoder's speed (frames/s).");
  cmd->add_option("FILE", args->file, "The .mvid file")->required();
  cmd->add_option("-o,--out", args->output,
                  "Output pattern with {frame}, e.g. out/f{frame:04}.ply or out/{frame}.obj\n"
                  "(required unless --no-write)");
  cmd->add_option("--level", args->level,
                  "Resolution level 0 (base mesh) .. L (default: the finest stored)")
      ->check(AtLeastZero());
  cmd->add_option("--frames", args->frames, "Frame range A:B (half-open), A:, :B or N");
  cmd->add_flag("--ascii", args->ascii, "Write ascii PLY instead of binary");
  cmd->add_flag("--no-write", args->no_write,
                "Decode every frame but write nothing; prints the decoding speed (one thread)");
  cmd->add_option("--json", args->json,
                  "Also write the timing as JSON: frames, seconds (decoding, file opening\n"
                  "excluded), open_seconds, frames_per_second, vertices, triangles");
  cmd->add_flag("--quiet,-q", args->quiet, "No progress bar or summary");
  cmd->callback([args, exit_code] { *exit_code = RunDecode(*args); });
}

}  // namespace meshvid::cli
