// `meshvid decode`: a .mvid to one mesh file per frame, at a chosen level; or, with
// --no-write, every frame decoded and timed without writing (decoder speed).
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "codec/dec/mvid_decoder.h"
#include "format/output_file.h"
#include "tools/cli/commands.h"
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
Status WriteDecodeJson(const DecodeArguments& args, int level, int frames, double open_seconds,
                       double seconds, const MvidInfo& info) {
  const nlohmann::json j = {{"file", args.file},
                            {"level", level},
                            {"frames", frames},
                            {"written", !args.no_write},
                            {"open_seconds", open_seconds},
                            {"seconds", seconds},
                            {"frames_per_second", seconds > 0 ? frames / seconds : 0.0},
                            {"vertices", info.vertices_per_level[level]},
                            {"triangles", info.triangles_per_level[level]}};
  return WriteFileAtomically(args.json, j.dump(2) + "\n");
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
  int first = 0, end = static_cast<int>(info.frame_count);
  if (!args.frames.empty()) {
    StatusOr<std::pair<int, int>> range = ParseFrameRange(args.frames, end);
    if (!range.ok()) return ReportError(range.status().WithContext("--frames"));
    first = range->first;
    end = range->second;
  }
  MeshWriteOptions write_options;
  write_options.ply_encoding = args.ascii ? PlyEncoding::kAscii : PlyEncoding::kBinaryLittleEndian;
  ProgressBar bar(args.quiet);
  const ProgressCallback progress = bar.Callback();
  const Clock::time_point start = Clock::now();
  const double open_seconds = std::chrono::duration<double>(start - open_start).count();
  for (int frame = first; frame < end; ++frame) {
    StatusOr<TriangleMesh> mesh = (*decoder)->DecodeFrame(frame, level);
    if (!mesh.ok()) return ReportError(mesh.status());
    if (!args.no_write) {
      const std::string path = pattern->Expand(frame);
      const Status written = WriteMesh(path, *mesh, write_options);
      if (!written.ok()) return ReportError(written);
    }
    ReportProgress(progress, "decoding", frame - first + 1, end - first);
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  bar.Finish();
  if (!args.json.empty()) {
    const Status written = WriteDecodeJson(args, level, end - first, open_seconds, seconds, info);
    if (!written.ok()) return ReportError(written);
  }
  if (!args.quiet && args.no_write) {
    std::fprintf(stderr,
                 "Decoded frames %d..%d of %s at level %d (%zu vertices, %zu triangles "
                 "each) in %.3f s: %.1f frames/s, nothing written\n",
                 first, end - 1, args.file.c_str(), level, info.vertices_per_level[level],
                 info.triangles_per_level[level], seconds,
                 seconds > 0 ? (end - first) / seconds : 0.0);
  } else if (!args.quiet) {
    std::fprintf(stderr,
                 "Decoded frames %d..%d of %s at level %d (%zu vertices, %zu triangles "
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
      ->check(CLI::NonNegativeNumber);
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
