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
#include <vector>

#include "codec/common/mesh.h"
#include "codec/dec/mvid_decoder.h"
#include "format/output_file.h"
#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/mvid_input.h"
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
  bool normals = false;
  bool no_write = false;
  bool quiet = false;
  bool allow_partial = false;
};

/// The frames decoded from one key group, and the size of each (the same for all of them).
struct DecodedKeyGroup {
  std::uint32_t key_group = 0;
  std::uint32_t first_frame = 0;
  std::uint32_t frames = 0;
  std::size_t vertices = 0;
  std::size_t triangles = 0;
};

/// Mean, least and most of a per-frame count over the decoded frames.
struct CountRange {
  double mean = 0;
  std::size_t min = 0;
  std::size_t max = 0;
};

CountRange RangeOf(const std::vector<DecodedKeyGroup>& groups,
                   std::size_t DecodedKeyGroup::*count) {
  CountRange range;
  if (groups.empty()) return range;
  range.min = range.max = groups.front().*count;
  double total = 0, frames = 0;
  for (const DecodedKeyGroup& g : groups) {
    range.min = std::min(range.min, g.*count);
    range.max = std::max(range.max, g.*count);
    total += double(g.*count) * g.frames;
    frames += g.frames;
  }
  range.mean = frames > 0 ? total / frames : 0;
  return range;
}

/// "2376 vertices, 4065 triangles each" for one key group; "2376..2553 vertices, 4065..4408
/// triangles, the same within each of 4 key groups" for several.
std::string SizeText(const std::vector<DecodedKeyGroup>& groups) {
  const CountRange v = RangeOf(groups, &DecodedKeyGroup::vertices);
  const CountRange t = RangeOf(groups, &DecodedKeyGroup::triangles);
  if (groups.size() <= 1) {
    return std::to_string(v.max) + " vertices, " + std::to_string(t.max) + " triangles each";
  }
  return std::to_string(v.min) + ".." + std::to_string(v.max) + " vertices, " +
         std::to_string(t.min) + ".." + std::to_string(t.max) +
         " triangles, the same within each of " + std::to_string(groups.size()) + " key groups";
}

/// Writes the timing of a decode and the size of its frames as JSON (for meshvid bench and
/// scripts): "vertices" and "triangles" are means over the decoded frames.
Status WriteDecodeJson(const DecodeArguments& args, int level, std::uint64_t frames,
                       double open_seconds, double seconds,
                       const std::vector<DecodedKeyGroup>& groups) {
  const CountRange v = RangeOf(groups, &DecodedKeyGroup::vertices);
  const CountRange t = RangeOf(groups, &DecodedKeyGroup::triangles);
  nlohmann::json key_groups = nlohmann::json::array();
  for (const DecodedKeyGroup& g : groups) {
    key_groups.push_back({{"key_group", g.key_group},
                          {"first_frame", g.first_frame},
                          {"frames", g.frames},
                          {"vertices", g.vertices},
                          {"triangles", g.triangles}});
  }
  const nlohmann::json j = {{"file", args.file},
                            {"level", level},
                            {"frames", frames},
                            {"written", !args.no_write},
                            {"open_seconds", open_seconds},
                            {"seconds", seconds},
                            {"frames_per_second", seconds > 0 ? double(frames) / seconds : 0.0},
                            {"vertices", v.mean},
                            {"vertices_min", v.min},
                            {"vertices_max", v.max},
                            {"triangles", t.mean},
                            {"triangles_min", t.min},
                            {"triangles_max", t.max},
                            {"key_groups", key_groups}};
  return WriteJsonOutput(args.json, DumpJson(j, 2) + "\n");
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
  StatusOr<std::unique_ptr<MvidDecoder>> decoder =
      MvidDecoder::OpenFile(args.file, {.allow_partial = args.allow_partial});
  if (!decoder.ok()) return ReportError(decoder.status());
  if (args.allow_partial) WarnIfPartial(args.file, (*decoder)->info());
  const MvidInfo& info = (*decoder)->info();
  const int level = args.level < 0 ? info.levels : args.level;
  if (level > info.levels) {
    return ReportError(InvalidArgumentError(args.file + " stores levels 0.." +
                                            std::to_string(info.levels) + ", not " +
                                            std::to_string(level)));
  }
  // Frame numbers are u32; --frames (int) can address the first 2^31 - 1 of them.
  std::uint32_t first = 0, end = info.frame_count;
  if (!args.frames.empty()) {
    const int addressable = static_cast<int>(
        std::min<std::uint32_t>(end, std::numeric_limits<int>::max()));
    StatusOr<std::pair<int, int>> range = FramesOption(args.frames, addressable);
    if (!range.ok()) return ReportError(range.status());
    first = static_cast<std::uint32_t>(range->first);
    end = static_cast<std::uint32_t>(range->second);
  }
  MeshWriteOptions write_options;
  write_options.ply_encoding = args.ascii ? PlyEncoding::kAscii : PlyEncoding::kBinaryLittleEndian;
  ProgressBar bar(args.quiet);
  const ProgressCallback progress = bar.Callback();
  std::vector<DecodedKeyGroup> groups;
  const Clock::time_point start = Clock::now();
  const double open_seconds = std::chrono::duration<double>(start - open_start).count();
  for (std::uint32_t frame = first; frame < end; ++frame) {
    StatusOr<TriangleMesh> mesh = (*decoder)->DecodeFrame(frame, level);
    if (!mesh.ok()) return ReportError(mesh.status());
    const std::uint32_t key_group = (*decoder)->current_key_group();
    if (groups.empty() || groups.back().key_group != key_group) {
      groups.push_back({key_group, frame, 0, mesh->vertex_count(), mesh->triangle_count()});
    }
    ++groups.back().frames;
    if (!args.no_write) {
      if (args.normals) mesh->normals = ComputeVertexNormals(*mesh);
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
    const Status written = WriteDecodeJson(args, level, end - first, open_seconds, seconds, groups);
    if (!written.ok()) return ReportError(written);
  }
  if (!args.quiet && args.no_write) {
    std::fprintf(stderr,
                 "Decoded frames %u..%u of %s at level %d (%s) in %.3f s: %.1f frames/s, nothing "
                 "written\n",
                 first, end - 1, args.file.c_str(), level, SizeText(groups).c_str(), seconds,
                 seconds > 0 ? (end - first) / seconds : 0.0);
  } else if (!args.quiet) {
    std::fprintf(stderr, "Decoded frames %u..%u of %s at level %d (%s) to %s\n", first, end - 1,
                 args.file.c_str(), level, SizeText(groups).c_str(), args.output.c_str());
  }
  return 0;
}

}  // namespace

void AddDecodeCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<DecodeArguments>();
  CLI::App* cmd = app.add_subcommand(
      "decode",
      "Decode a .mvid into one mesh file per frame (binary PLY, ascii PLY or OBJ by the\n"
      "pattern's extension). At a level, every frame of a key group has the same triangles (a\n"
      "new key group may have others). With --no-write, decode every frame without writing\n"
      "it and report the decoder's speed (frames/s).");
  cmd->add_option("FILE", args->file, "The .mvid file")->required();
  cmd->add_option("-o,--out", args->output,
                  "Output pattern with {frame}, e.g. out/f{frame:04}.ply or out/{frame}.obj\n"
                  "(required unless --no-write)");
  cmd->add_option("--level", args->level,
                  "Resolution level 0 (base mesh) .. L (default: the finest stored)")
      ->check(AtLeastZero());
  cmd->add_option("--frames", args->frames, "Frame range A:B (half-open), A:, :B or N")
      ->type_name("A:B");
  cmd->add_flag("--ascii", args->ascii, "Write ascii PLY instead of binary");
  cmd->add_flag("--normals", args->normals,
                "Also write per-vertex normals (area-weighted; PLY nx ny nz, OBJ vn), as\n"
                "renderers expect for smooth shading");
  cmd->add_flag("--no-write", args->no_write,
                "Decode every frame but write nothing; prints the decoding speed (one thread)");
  cmd->add_option("--json", args->json,
                  JsonOptionHelp("Also write the timing and the sizes per key group"))
      ->type_name("FILE|-");
  AddAllowPartialFlag(cmd, &args->allow_partial);
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar and no summary");
  cmd->callback([args, exit_code] { *exit_code = RunDecode(*args); });
}

}  // namespace meshvid::cli
