// `meshvid export`: a .mvid to files other tools open: OBJ + PC2 mesh caches (Blender's Mesh
// Cache modifier) per key group, or a glTF 2.0 binary with a skin and an animation.
#include <cctype>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "codec/dec/mvid_decoder.h"
#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/mvid_input.h"
#include "tools/cli/option_checks.h"
#include "tools/cli/terminal.h"
#include "tools/export/gltf_export.h"
#include "tools/export/mesh_cache_export.h"
#include "tools/io/file_pattern.h"

namespace meshvid::cli {
namespace {

struct ExportArguments {
  std::string file;
  std::string output;
  int level = -1;
  std::string frames;
  std::string json;
  bool quiet = false;
  bool allow_partial = false;
};

bool EndsWith(const std::string& text, const std::string& suffix) {
  if (text.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(text[text.size() - suffix.size() + i])) !=
        suffix[i]) {
      return false;
    }
  }
  return true;
}

int RunExport(const ExportArguments& args) {
  const bool obj = EndsWith(args.output, ".obj");
  const bool glb = EndsWith(args.output, ".glb");
  if (!obj && !glb) {
    std::fprintf(stderr, "meshvid: -o must end in .obj (OBJ + PC2) or .glb (glTF binary)\n");
    return 2;
  }
  StatusOr<std::unique_ptr<MvidDecoder>> decoder =
      MvidDecoder::OpenFile(args.file, {.allow_partial = args.allow_partial});
  if (!decoder.ok()) return ReportError(decoder.status());
  if (args.allow_partial) WarnIfPartial(args.file, (*decoder)->info());
  ExportOptions options;
  options.level = args.level;
  if (!args.frames.empty()) {
    const int addressable = static_cast<int>(std::min<std::uint32_t>(
        (*decoder)->info().frame_count, std::numeric_limits<int>::max()));
    StatusOr<std::pair<int, int>> range = FramesOption(args.frames, addressable);
    if (!range.ok()) return ReportError(range.status());
    options.first_frame = static_cast<std::uint32_t>(range->first);
    options.end_frame = static_cast<std::uint32_t>(range->second);
  }
  ProgressBar bar(args.quiet);
  if (obj) {
    StatusOr<std::vector<MeshCacheFiles>> files =
        ExportMeshCache(**decoder, args.output, options, bar.Callback());
    bar.Finish();
    if (!files.ok()) return ReportError(files.status());
    if (!args.json.empty()) {
      nlohmann::json list = nlohmann::json::array();
      for (const MeshCacheFiles& f : *files) {
        list.push_back({{"key_group", f.key_group},
                        {"first_frame", f.first_frame},
                        {"frames", f.frame_count},
                        {"obj", ToValidUtf8(f.obj)},
                        {"pc2", ToValidUtf8(f.pc2)}});
      }
      const Status written = WriteJsonOutput(args.json, DumpJson({{"files", list}}, 2) + "\n");
      if (!written.ok()) return ReportError(written);
    }
    if (!args.quiet) {
      for (const MeshCacheFiles& f : *files) {
        std::fprintf(stderr, "key group %u, frames %u..%u: %s + %s\n", f.key_group,
                     f.first_frame, f.first_frame + f.frame_count - 1, f.obj.c_str(),
                     f.pc2.c_str());
      }
    }
    return 0;
  }
  StatusOr<GltfExportStats> stats = ExportGltf(**decoder, args.output, options, bar.Callback());
  bar.Finish();
  if (!stats.ok()) return ReportError(stats.status());
  if (!args.json.empty()) {
    const nlohmann::json j = {{"file", ToValidUtf8(args.output)},
                              {"key_groups", stats->key_groups},
                              {"joints", stats->joints},
                              {"frames", stats->frames},
                              {"bytes", stats->bytes}};
    const Status written = WriteJsonOutput(args.json, DumpJson(j, 2) + "\n");
    if (!written.ok()) return ReportError(written);
  }
  if (!args.quiet) {
    std::fprintf(stderr, "%s: %s, %s, %s at %.3g fps (%zu bytes)\n", args.output.c_str(),
                 Count(stats->key_groups, "key group").c_str(),
                 Count(stats->joints, "joint").c_str(), Count(stats->frames, "frame").c_str(),
                 (*decoder)->info().frame_rate, stats->bytes);
  }
  return 0;
}

}  // namespace

void AddExportCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<ExportArguments>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Export a .mvid for other tools, by the extension of -o:\n"
      "  OUT.obj  the decoded surface at --level as OBJ + PC2 (Point Cache 2) mesh caches, one\n"
      "           pair per key group (its own connectivity): OUT.obj + OUT.pc2 for one key\n"
      "           group, else OUT_kg0.obj + OUT_kg0.pc2, OUT_kg1.obj, ... Blender: import the\n"
      "           OBJ (keep vertex order), add a Mesh Cache modifier reading the PC2.\n"
      "  OUT.glb  glTF 2.0 binary: each key group's base mesh with a skin (one joint per\n"
      "           segment, blend weights as joint weights, at most 4 per vertex) and the\n"
      "           segments' per-frame transforms as an animation; each key group's mesh is\n"
      "           shown only during its frames. Coarse motion only (no displacements).");
  cmd->add_option("FILE", args->file, "The .mvid file")->required();
  cmd->add_option("-o,--out", args->output, "Output file: NAME.obj or NAME.glb")->required();
  cmd->add_option("--level", args->level,
                  "Resolution level of the OBJ + PC2 export, 0 (base) .. L (default: finest)")
      ->check(AtLeastZero());
  cmd->add_option("--frames", args->frames, "Frame range A:B (half-open), A:, :B or N")
      ->type_name("A:B");
  cmd->add_option("--json", args->json, JsonOptionHelp("Also write what was written"))
      ->type_name("FILE|-");
  AddAllowPartialFlag(cmd, &args->allow_partial);
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar and no summary");
  cmd->callback([args, exit_code] { *exit_code = RunExport(*args); });
}

}  // namespace meshvid::cli
