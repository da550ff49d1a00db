// `meshvid info`: what a .mvid holds, and with --check whether it is intact.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "codec/dec/mvid_decoder.h"
#include "format/validate.h"
#include "tools/io/capture.h"
#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/mvid_input.h"
#include "tools/cli/terminal.h"

namespace meshvid::cli {
namespace {

struct InfoArguments {
  std::string file;
  bool check = false;
  std::string json;  ///< --json TARGET: a file, or "-" for stdout
};

/// Decodes every group once (transforms, displacement and colour video), so a damaged stream
/// is found.
Status DecodeEveryGroup(MvidDecoder& decoder, const ProgressCallback& progress) {
  const MvidInfo& info = decoder.info();
  std::vector<float> displacements;
  std::vector<Colour> colours;
  for (std::uint32_t frame = 0; frame < info.frame_count; ++frame) {
    MESHVID_RETURN_IF_ERROR(decoder.DecodeDisplacements(frame, &displacements));
    // The colour video is decoded only when asked for.
    if (info.colour) MESHVID_RETURN_IF_ERROR(decoder.DecodeColours(frame, 0, &colours));
    MESHVID_RETURN_IF_ERROR(decoder.DecodeTransforms(frame).status());
    if (!ReportProgress(progress, "checking", frame + 1, info.frame_count)) {
      return CancelledError("cancelled");
    }
  }
  return Status::Ok();
}

/// True if `spec` names a capture (a manifest, a folder holding one, a file pattern or a
/// Stanford .conf) rather than a .mvid.
bool IsCaptureSpec(const std::string& spec) {
  if (spec.ends_with(".mvid")) return false;
  return spec.ends_with(".json") || spec.ends_with(".conf") ||
         spec.find('{') != std::string::npos || std::filesystem::is_directory(spec);
}

/// `meshvid info CAPTURE`: the capture's views, frames and rate; with --check, every view
/// file is loaded and validated too. Scripts read the frame count from its JSON (the chunk
/// planner of scripts/cluster does).
int RunCaptureInfo(const InfoArguments& args) {
  StatusOr<std::unique_ptr<CaptureSequence>> capture = CaptureSequence::Open(args.file);
  if (!capture.ok()) return ReportError(capture.status());
  const CaptureInfo& info = (*capture)->info();
  if (args.check) {
    ProgressBar bar(args.json == "-");
    const ProgressCallback progress = bar.Callback();
    for (int frame = 0; frame < info.frame_count; ++frame) {
      StatusOr<std::vector<TriangleMesh>> views = (*capture)->LoadFrame(frame);
      if (!views.ok()) {
        bar.Finish();
        return ReportError(views.status());
      }
      ReportProgress(progress, "checking", frame + 1, info.frame_count);
    }
    bar.Finish();
  }
  nlohmann::json view_names = nlohmann::json::array();
  std::string names;
  for (const CaptureView& view : info.views) {
    view_names.push_back(view.name);
    names += (names.empty() ? "" : " ") + view.name;
  }
  if (!args.json.empty()) {
    const nlohmann::json j = {{"capture", args.file},
                              {"frames", info.frame_count},
                              {"views", view_names},
                              {"frame_rate", info.frame_rate},
                              {"duration_s", info.frame_count / info.frame_rate},
                              {"units", info.units},
                              {"checked", args.check}};
    const Status written = WriteJsonOutput(args.json, DumpJson(j, 2) + "\n");
    if (!written.ok()) return ReportError(written);
    if (args.json == "-") return 0;
  }
  std::printf("%s: capture of %s x %s at %.3g fps (%.2f s), units %s\n", args.file.c_str(),
              Count(info.views.size(), "view").c_str(), Count(info.frame_count, "frame").c_str(),
              info.frame_rate, info.frame_count / info.frame_rate, info.units.c_str());
  std::printf("  views          %s\n", names.c_str());
  if (args.check) std::printf("  check          ok: every view file of every frame loads\n");
  return 0;
}

int RunInfo(const InfoArguments& args) {
  if (IsCaptureSpec(args.file)) return RunCaptureInfo(args);
  if (args.check) {
    StatusOr<ValidationReport> report = ValidateContainerFile(args.file);
    if (!report.ok()) return ReportError(report.status());
    if (args.json != "-") std::fputs(report->ToText().c_str(), stdout);
    // The report above lists the problems; stderr says only that the check failed.
    if (!report->ok() && args.json != "-") {
      std::fprintf(stderr, "meshvid: %s: the check failed (%s, listed above)\n", args.file.c_str(),
                   Count(report->errors.size(), "problem").c_str());
      return 1;
    }
    if (!report->ok()) return ReportError(report->ToStatus());
  }
  // info describes a partial file too (and says so); --check fails on it.
  StatusOr<std::unique_ptr<MvidDecoder>> decoder =
      MvidDecoder::OpenFile(args.file, {.allow_partial = true});
  if (!decoder.ok()) return ReportError(decoder.status());
  const MvidInfo& info = (*decoder)->info();
  StatusOr<MvidStreamSizes> sizes = (*decoder)->MeasureStreams();
  if (!sizes.ok()) return ReportError(sizes.status());
  if (args.check) {
    ProgressBar bar(args.json == "-");
    const Status decoded = DecodeEveryGroup(**decoder, bar.Callback());
    bar.Finish();
    if (!decoded.ok()) return ReportError(decoded.WithContext(args.file));
  }
  // Every key group's base size and bytes (each one's BASE and MOTN are decoded once).
  std::vector<MvidKeyGroupInfo> key_groups;
  for (std::uint32_t k = 0; k < info.key_groups.size(); ++k) {
    StatusOr<MvidKeyGroupInfo> described = (*decoder)->DescribeKeyGroup(k);
    if (!described.ok()) return ReportError(described.status());
    key_groups.push_back(*std::move(described));
  }
  WarnIfPartial(args.file, info);
  const double frames = std::max<double>(1, info.frame_count);
  const double bytes_per_frame = info.file_bytes / frames;
  const double mbits = bytes_per_frame * 8 * info.frame_rate / 1e6;
  if (!args.json.empty()) {
    nlohmann::json key_group_list = nlohmann::json::array();
    for (std::size_t k = 0; k < key_groups.size(); ++k) {
      const MvidKeyGroupInfo& g = key_groups[k];
      key_group_list.push_back({{"first_frame", g.span.first_frame},
                                {"frames", g.span.frame_count},
                                {"groups", g.span.gof_count},
                                {"base", {{"vertices", g.base_vertices},
                                          {"triangles", g.base_triangles}}},
                                {"segments", g.segments},
                                {"picture", {{"width", g.picture_width},
                                             {"height", g.picture_height}}},
                                {"vertices_per_level", g.vertices_per_level},
                                {"triangles_per_level", g.triangles_per_level},
                                {"bytes", sizes->key_group_bytes[k]}});
    }
    nlohmann::json j = {
        {"file", args.file},
        {"frames", info.frame_count},
        {"declared_frames", info.declared_frame_count},
        {"partial", info.partial()},
        {"frame_rate", info.frame_rate},
        {"duration_s", info.frame_count / info.frame_rate},
        {"groups", info.gof_count},
        {"frames_per_group", info.gof_size},
        {"levels", info.levels},
        {"indexed", info.indexed},
        {"format_version", info.format_version},
        {"key_groups", key_group_list},
        {"codec", std::string(VideoCodecName(info.codec))},
        {"picture", {{"width", info.picture_width}, {"height", info.picture_height}}},
        {"base", {{"vertices", info.base_vertices}, {"triangles", info.base_triangles}}},
        {"segments", info.segments},
        {"bytes",
         {{"file", info.file_bytes},
          {"base_mesh", sizes->base_bytes},
          {"motion_model", sizes->motion_bytes},
          {"transforms", sizes->transform_bytes},
          {"video", sizes->video_bytes},
          {"colour", sizes->colour_bytes},
          {"per_frame", bytes_per_frame}}},
        {"colour", info.colour},
        {"mbit_per_s", mbits},
        {"vertices_per_level", info.vertices_per_level},
        {"triangles_per_level", info.triangles_per_level},
        {"checked", args.check},
        {"metadata", nlohmann::json::parse(info.metadata_json.empty() ? "{}" : info.metadata_json,
                                           nullptr, /*allow_exceptions=*/false)}};
    const Status written = WriteJsonOutput(args.json, DumpJson(j, 2) + "\n");
    if (!written.ok()) return ReportError(written);
    if (args.json == "-") return 0;
  }
  std::printf("%s: %s at %.3g fps (%.2f s) in %s of up to %s%s\n", args.file.c_str(),
              Count(info.frame_count, "frame").c_str(), info.frame_rate,
              info.frame_count / info.frame_rate, Count(info.gof_count, "group").c_str(),
              Count(info.gof_size, "frame").c_str(),
              info.indexed ? "" : " (no index: groups found by scanning)");
  std::printf("  key groups     %zu (a base mesh each; the same triangles within each)\n",
              key_groups.size());
  if (info.partial()) {
    std::printf("  partial        %u of the %u frames the header promises are readable\n",
                info.frame_count, info.declared_frame_count);
  }
  std::printf("  base mesh      %zu vertices, %zu triangles in key group 0; all bases %s (Draco)\n",
              info.base_vertices, info.base_triangles, Kilobytes(sizes->base_bytes).c_str());
  std::printf("  motion         %s in key group 0: blend weights %s, transforms %s\n",
              Count(info.segments, "segment").c_str(), Kilobytes(sizes->motion_bytes).c_str(),
              Kilobytes(sizes->transform_bytes).c_str());
  std::printf("  displacements  %s 10-bit %dx%d, %s\n",
              std::string(VideoCodecName(info.codec)).c_str(), info.picture_width,
              info.picture_height, Kilobytes(sizes->video_bytes).c_str());
  if (info.colour) {
    std::printf("  colour         %s 8-bit Y Cb Cr 4:4:4 %dx%d, %s\n",
                std::string(VideoCodecName(info.codec)).c_str(), info.picture_width,
                info.picture_height, Kilobytes(sizes->colour_bytes).c_str());
  }
  std::printf("  total          %s = %.0f bytes per frame = %.3f Mbit/s at %.3g fps\n",
              Kilobytes(info.file_bytes).c_str(), bytes_per_frame, mbits, info.frame_rate);
  std::printf("  key group  first frame  frames  base vertices  segments  bytes\n");
  for (std::size_t k = 0; k < key_groups.size(); ++k) {
    const MvidKeyGroupInfo& g = key_groups[k];
    std::printf("  %9zu  %11u  %6u  %13zu  %8u  %s\n", k, g.span.first_frame,
                g.span.frame_count, g.base_vertices, g.segments,
                Kilobytes(sizes->key_group_bytes[k]).c_str());
  }
  std::printf("  level  vertices  triangles (key group 0)\n");
  for (int level = 0; level <= info.levels; ++level) {
    std::printf("  %5d  %8zu  %9zu\n", level, info.vertices_per_level[level],
                info.triangles_per_level[level]);
  }
  if (!info.metadata_json.empty()) std::printf("  metadata       %s\n", info.metadata_json.c_str());
  if (args.check) std::printf("  check          ok: every chunk, CRC and group decodes\n");
  return 0;
}

}  // namespace

void AddInfoCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<InfoArguments>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Show what a .mvid holds: frames, rate, groups, levels (vertices and triangles of each),\n"
      "the bytes of every stream, bytes per frame and Mbit/s. With --check, also validate\n"
      "every chunk and CRC and decode every group; exits 1 if anything is wrong.\n"
      "Given a capture (manifest.json, a folder holding one, a {frame}/{view} pattern or a\n"
      ".conf), show its views, frames and rate; with --check, load every view file.");
  cmd->add_option("FILE", args->file, "The .mvid file, or a capture")->required();
  cmd->add_flag("--check", args->check,
                "Validate the file and decode every group (a capture: load every view file)");
  cmd->add_option("--json", args->json,
                  JsonOptionHelp("Also write what the file holds") +
                      "\n(with -, instead of the text)")
      ->type_name("FILE|-");
  cmd->callback([args, exit_code] { *exit_code = RunInfo(*args); });
}

}  // namespace meshvid::cli
