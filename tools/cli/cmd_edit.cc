// `meshvid edit`: a frame's surface moved in a modelling tool becomes a detail edit that every
// frame of its key group takes (codec/enc/coding/detail_edit.h).
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "codec/dec/mvid_decoder.h"
#include "codec/enc/coding/detail_edit.h"
#include "tools/cli/commands.h"
#include "tools/cli/terminal.h"
#include "tools/io/mesh_io.h"

namespace meshvid::cli {
namespace {

struct EditArguments {
  std::string input;
  std::string output;
  std::string edited;
  DetailEditOptions options;
  bool quiet = false;
};

/// Reads the edited mesh into `options.edited`, after checking that it is the frame at that
/// level as `meshvid decode` writes it: the same triangles, vertex for vertex.
Status ReadEditedFrame(const std::string& input, const std::string& edited,
                       DetailEditOptions* options) {
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<MvidDecoder> decoder, MvidDecoder::OpenFile(input));
  const MvidInfo& info = decoder->info();
  if (options->frame >= info.frame_count) {
    return InvalidArgumentError(input + " has frames 0.." + std::to_string(info.frame_count - 1) +
                                "; --frame " + std::to_string(options->frame) + " is not one");
  }
  if (options->level < 0) options->level = info.levels;
  if (options->level > info.levels) {
    return InvalidArgumentError(input + " stores levels 0.." + std::to_string(info.levels) +
                                "; --level " + std::to_string(options->level) + " is not one");
  }
  MESHVID_ASSIGN_OR_RETURN(TriangleMesh mesh, ReadMesh(edited));
  MESHVID_ASSIGN_OR_RETURN(const std::vector<Triangle>* triangles,
                           decoder->TrianglesOf(options->frame, options->level));
  const std::string frame =
      "frame " + std::to_string(options->frame) + " at level " + std::to_string(options->level);
  const std::string how = " (write it with `meshvid decode " + input + " --frames " +
                          std::to_string(options->frame) + ":" +
                          std::to_string(options->frame + 1) + " --level " +
                          std::to_string(options->level) + "`, then move its vertices only)";
  std::vector<Eigen::Vector3f> decoded;
  MESHVID_RETURN_IF_ERROR(decoder->DecodePositions(options->frame, options->level, &decoded));
  if (mesh.vertex_count() != decoded.size() || mesh.triangles != *triangles) {
    return InvalidArgumentError(
        edited + ": " + std::to_string(mesh.vertex_count()) + " vertices and " +
        std::to_string(mesh.triangles.size()) + " triangles, not those of " + frame + " (" +
        std::to_string(decoded.size()) + " and " + std::to_string(triangles->size()) + ")" + how);
  }
  options->edited = std::move(mesh.positions);
  return Status::Ok();
}

int RunEdit(EditArguments& args) {
  const auto start = std::chrono::steady_clock::now();
  if (Status read = ReadEditedFrame(args.input, args.edited, &args.options); !read.ok()) {
    return ReportError(read);
  }
  ProgressBar bar(args.quiet);
  args.options.progress = bar.Callback();
  StatusOr<DetailEditSummary> summary = EditDetail(args.input, args.output, args.options);
  bar.Finish();
  if (!summary.ok()) return ReportError(summary.status());
  if (!args.quiet) {
    const DetailEditSummary& s = *summary;
    std::fprintf(stderr,
                 "Edited %s into %s in %.1f s: frame %u's edit carried to key group %u (frames "
                 "%u..%u), %s coded again\n"
                 "  edit           %zu vertices moved, by %.3g at most along the surface's "
                 "normal\n",
                 args.input.c_str(), args.output.c_str(), SecondsSince(start), args.options.frame,
                 s.key_group, s.first_frame, s.first_frame + s.frame_count - 1,
                 Count(s.groups_coded, "group").c_str(), s.change.moved_vertices,
                 s.change.largest_normal_move);
    if (s.change.largest_tangential_move > 0) {
      std::fprintf(stderr,
                   "  not carried    moves across the normal, up to %.3g: displacements move a "
                   "vertex along its normal only\n",
                   s.change.largest_tangential_move);
    }
    if (s.ranges_widened > 0) {
      std::fprintf(stderr, "  range          widened in %s to hold the edit\n",
                   Count(s.ranges_widened, "group").c_str());
    }
    std::fprintf(stderr, "  file           %s -> %s\n", Kilobytes(double(s.input_bytes)).c_str(),
                 Kilobytes(double(s.output_bytes)).c_str());
  }
  return 0;
}

}  // namespace

void AddEditCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<EditArguments>();
  CLI::App* cmd = app.add_subcommand(
      "edit",
      "Carry a sculpted frame through its key group: EDITED is frame --frame at --level as\n"
      "`meshvid decode` wrote it, with vertices moved in any modelling tool. Each vertex's move\n"
      "along the surface's normal becomes a change of the detail, which every frame of the key\n"
      "group takes on its own moving surface (moves across the normal are not carried; the\n"
      "summary says how large they were). Only that key group's displacement video is coded\n"
      "again; base meshes, motion, colour and every other group are copied byte for byte.");
  cmd->add_option("FILE", args->input, "The .mvid to edit")->required()->check(CLI::ExistingFile);
  cmd->add_option("--frame", args->options.frame, "The frame EDITED is")->required();
  cmd->add_option("--edited", args->edited, "The edited frame (PLY or OBJ)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--level", args->options.level,
                  "The level EDITED was decoded at (default: the finest stored)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("-o,--output", args->output, "The edited .mvid")->required();
  cmd->add_option("--quality", args->options.quality,
                  "0 (smallest) .. 100 (finest): the quantiser of the key group's video coded "
                  "again, as `meshvid encode` sets it (a file does not record its own); FFV1 "
                  "is lossless")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
  cmd->add_option("--effort", args->options.effort, "Video encoder effort 0 (fastest) .. 9")
      ->capture_default_str()
      ->check(CLI::Range(0, 9));
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar and no summary");
  cmd->callback([args, exit_code] { *exit_code = RunEdit(*args); });
}

}  // namespace meshvid::cli
