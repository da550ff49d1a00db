#include "tools/bench/baseline.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "codec/common/progress.h"
#include "codec/common/subdivision.h"
#include "codec/dec/base_mesh_decoder.h"
#include "codec/enc/coding/base_mesh_encoder.h"
#include "codec/enc/fusion/decimation.h"
#include "codec/enc/key_groups/colour.h"
#include "codec/enc/key_groups/detail.h"
#include "format/output_file.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

using Clock = std::chrono::steady_clock;  // timed with SecondsSince (codec/common/progress.h)

std::string FramePath(const std::string& folder, int frame, const char* extension) {
  char name[32];
  std::snprintf(name, sizeof(name), "/f%04d.%s", frame, extension);
  return folder + name;
}

/// How far along its normal a fused vertex looks for the views' surfaces, and how far from
/// the views' median a hit may be, as fractions of the mesh's bounding-box diagonal: the
/// encoder's displacement range and outlier distance (0.005 of the scene's size), which the
/// fusion's vertices, within the sensors' noise of the data, are well inside.
constexpr float kColourShotFraction = 0.005f;

}  // namespace

Status ColourVerticesFromViews(std::span<const TriangleMesh> views,
                               std::span<const ViewCalibration> cameras, TriangleMesh* mesh) {
  MESHVID_ASSIGN_OR_RETURN(const RegularSubdivision lattice, RegularSubdivision::Create(*mesh, 0));
  const float diagonal = BoundingBox(*mesh).diagonal().norm();
  DetailOptions detail;
  detail.shot.max_distance = kColourShotFraction * diagonal;
  detail.outlier_distance = kColourShotFraction * diagonal;
  std::vector<float> displacements;
  ColourObservations observations;
  MESHVID_RETURN_IF_ERROR(MeasureDisplacements(lattice, mesh->positions, views, detail,
                                               &displacements, cameras, &observations)
                              .status());
  std::array<std::vector<float>, 3> fused;
  FuseColours(observations, EstimateExposureGains(observations), &fused);
  // The encoder's fill for colour, over a run of one frame.
  std::array<std::vector<std::vector<float>>, 3> channels;
  for (int c = 0; c < 3; ++c) channels[c].push_back(std::move(fused[c]));
  std::array<std::vector<float>, 3> last_seen;
  mesh->colours = std::move(FillColours(SampleGraph::Build(lattice), &channels, &last_seen)[0]);
  return Status::Ok();
}

std::string BaselineSettingFolder(std::size_t target_vertices, int position_bits) {
  const std::string bits = "b" + std::to_string(position_bits);
  return target_vertices == 0 ? bits : "v" + std::to_string(target_vertices) + "-" + bits;
}

StatusOr<BaselineSummary> RunBaseline(const CaptureSequence& capture,
                                      const BaselineOptions& options,
                                      const ProgressCallback& progress) {
  if (options.position_bits.empty()) {
    return InvalidArgumentError("the baseline needs at least one Draco position_bits setting");
  }
  for (int bits : options.position_bits) {
    if (bits < 1 || bits > 30) {
      return InvalidArgumentError("Draco position bits must be 1..30 (got " + std::to_string(bits) +
                                  ")");
    }
  }
  for (std::size_t target : options.vertex_targets) {
    if (target < 4) {
      return InvalidArgumentError("a decimation target must be at least 4 vertices (got " +
                                  std::to_string(target) + ")");
    }
  }
  BaselineSummary summary;
  summary.frames = capture.frame_count();
  summary.frame_rate = capture.info().frame_rate;
  // The meshes of a frame, one per target (index 0 and no target: the full fused mesh).
  std::vector<std::size_t> targets = options.vertex_targets;
  if (targets.empty()) targets.push_back(0);
  std::vector<std::string> folders;
  std::vector<std::size_t> mesh_of_setting;
  for (std::size_t t = 0; t < targets.size(); ++t) {
    for (int bits : options.position_bits) {
      BaselineSetting setting;
      setting.position_bits = bits;
      setting.target_vertices = targets[t];
      if (!options.out_dir.empty()) {
        const std::string folder = options.out_dir + "/" + BaselineSettingFolder(targets[t], bits);
        std::error_code error;
        std::filesystem::create_directories(folder, error);
        if (error) return IoError(folder + ": cannot create: " + error.message());
        folders.push_back(folder);
        setting.pattern = folder + "/f{frame:04}.ply";
      }
      summary.settings.push_back(setting);
      mesh_of_setting.push_back(t);
    }
  }
  BaseMeshEncoding encoding;
  encoding.encoding_speed = options.draco_speed;
  encoding.allow_reorder = true;  // edgebreaker: what a per-frame player streams
  MeshWriteOptions write_options;
  write_options.write_normals = false;
  const std::vector<ViewCalibration> cameras = capture.view_cameras();

  for (int frame = 0; frame < summary.frames; ++frame) {
    const std::string where = "baseline frame " + std::to_string(frame);
    Clock::time_point start = Clock::now();
    StatusOr<std::vector<TriangleMesh>> views = capture.LoadFrame(frame);
    if (!views.ok()) return views.status().WithContext(where);
    summary.load_seconds += SecondsSince(start);

    start = Clock::now();
    StatusOr<TriangleMesh> fused = FuseRangeMeshes(*views, options.fusion);
    if (!fused.ok()) return fused.status().WithContext(where + ": fusion");
    summary.fuse_seconds += SecondsSince(start);

    start = Clock::now();
    std::vector<TriangleMesh> meshes;
    for (std::size_t target : targets) {
      if (target == 0 || fused->vertex_count() <= target) {
        meshes.push_back(*fused);
        continue;
      }
      DecimationOptions decimation;
      decimation.target_vertices = target;
      StatusOr<TriangleMesh> decimated = DecimateMesh(*fused, decimation);
      if (!decimated.ok()) return decimated.status().WithContext(where + ": decimation");
      meshes.push_back(std::move(*decimated));
    }
    summary.decimate_seconds += SecondsSince(start);
    const bool colour = options.colour && ViewsHaveColour(*views);
    std::vector<double> colour_seconds(meshes.size(), 0.0);
    if (colour) {
      for (std::size_t t = 0; t < meshes.size(); ++t) {
        start = Clock::now();
        const Status coloured = ColourVerticesFromViews(*views, cameras, &meshes[t]);
        if (!coloured.ok()) return coloured.WithContext(where + ": colour");
        colour_seconds[t] = SecondsSince(start);
        summary.colour_seconds += colour_seconds[t];
      }
    }
    views->clear();

    for (std::size_t s = 0; s < summary.settings.size(); ++s) {
      BaselineSetting& setting = summary.settings[s];
      encoding.position_bits = setting.position_bits;
      setting.colour_seconds += colour_seconds[mesh_of_setting[s]];
      start = Clock::now();
      encoding.code_colours = colour;
      StatusOr<EncodedBaseMesh> encoded = EncodeBaseMesh(meshes[mesh_of_setting[s]], encoding);
      if (!encoded.ok()) return encoded.status().WithContext(where + ": Draco");
      setting.encode_seconds += SecondsSince(start);
      setting.bytes_total += encoded->bytes.size();
      if (colour) {
        // The colour's share: the same mesh coded again without it (not timed).
        encoding.code_colours = false;
        StatusOr<EncodedBaseMesh> plain = EncodeBaseMesh(meshes[mesh_of_setting[s]], encoding);
        if (!plain.ok()) return plain.status().WithContext(where + ": Draco");
        setting.colour_bytes_total +=
            encoded->bytes.size() - std::min(encoded->bytes.size(), plain->bytes.size());
      }

      start = Clock::now();
      StatusOr<TriangleMesh> decoded =
          DecodeBaseMesh(encoded->bytes, colour ? VertexColours::kRead : VertexColours::kIgnore);
      if (!decoded.ok()) return decoded.status().WithContext(where + ": Draco decoding");
      setting.decode_seconds += SecondsSince(start);
      setting.vertices += decoded->vertex_count();
      setting.triangles += decoded->triangle_count();
      if (!folders.empty()) {
        MESHVID_RETURN_IF_ERROR(
            WriteMesh(FramePath(folders[s], frame, "ply"), *decoded, write_options));
        const std::string bitstream(encoded->bytes.begin(), encoded->bytes.end());
        MESHVID_RETURN_IF_ERROR(WriteFileAtomically(FramePath(folders[s], frame, "drc"), bitstream));
      }
    }
    if (!ReportProgress(progress, "baseline", frame + 1, summary.frames)) {
      return CancelledError("baseline cancelled");
    }
  }
  for (BaselineSetting& setting : summary.settings) {
    if (summary.frames > 0) {
      setting.vertices /= summary.frames;
      setting.triangles /= summary.frames;
    }
  }
  return summary;
}

std::string BaselineSummaryToJson(const BaselineSummary& summary) {
  nlohmann::json j;
  j["frames"] = summary.frames;
  j["frame_rate"] = summary.frame_rate;
  j["load_seconds"] = summary.load_seconds;
  j["fuse_seconds"] = summary.fuse_seconds;
  j["decimate_seconds"] = summary.decimate_seconds;
  j["colour_seconds"] = summary.colour_seconds;
  j["settings"] = nlohmann::json::array();
  for (const BaselineSetting& s : summary.settings) {
    j["settings"].push_back({{"position_bits", s.position_bits},
                             {"target_vertices", s.target_vertices},
                             {"bytes_total", s.bytes_total},
                             {"colour_bytes_total", s.colour_bytes_total},
                             {"colour_seconds", s.colour_seconds},
                             {"encode_seconds", s.encode_seconds},
                             {"decode_seconds", s.decode_seconds},
                             {"vertices", s.vertices},
                             {"triangles", s.triangles},
                             {"pattern", s.pattern}});
  }
  return j.dump(2) + "\n";
}

StatusOr<BaselineSummary> ParseBaselineSummary(const std::string& text, const std::string& name) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return CorruptError(name + ": not a JSON object");
  try {
    BaselineSummary summary;
    summary.frames = j.at("frames").get<int>();
    summary.frame_rate = j.at("frame_rate").get<double>();
    summary.load_seconds = j.at("load_seconds").get<double>();
    summary.fuse_seconds = j.at("fuse_seconds").get<double>();
    summary.decimate_seconds = j.value("decimate_seconds", 0.0);
    summary.colour_seconds = j.value("colour_seconds", 0.0);
    for (const nlohmann::json& s : j.at("settings")) {
      BaselineSetting setting;
      setting.position_bits = s.at("position_bits").get<int>();
      setting.target_vertices = s.value("target_vertices", std::size_t{0});
      setting.bytes_total = s.at("bytes_total").get<std::size_t>();
      // A summary without it was written before the baseline coded colour: it fails, so a
      // resumed bench runs the baseline again rather than mix figures with and without colour.
      setting.colour_bytes_total = s.at("colour_bytes_total").get<std::size_t>();
      setting.colour_seconds = s.value("colour_seconds", 0.0);
      setting.encode_seconds = s.at("encode_seconds").get<double>();
      setting.decode_seconds = s.at("decode_seconds").get<double>();
      setting.vertices = s.at("vertices").get<double>();
      setting.triangles = s.at("triangles").get<double>();
      setting.pattern = s.at("pattern").get<std::string>();
      summary.settings.push_back(setting);
    }
    return summary;
  } catch (const std::exception& e) {
    return CorruptError(name + ": " + e.what());
  }
}

StatusOr<DracoDecodeSummary> DecodeDracoFrames(const std::string& folder) {
  std::vector<std::string> paths;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    if (entry.path().extension() == ".drc") paths.push_back(entry.path().string());
  }
  if (error) return NotFoundError(folder + ": cannot list: " + error.message());
  if (paths.empty()) return NotFoundError(folder + ": no .drc file");
  std::sort(paths.begin(), paths.end());
  DracoDecodeSummary summary;
  for (const std::string& path : paths) {
    MESHVID_ASSIGN_OR_RETURN(const std::string text, ReadTextFile(path));
    const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(text.data()),
                                              text.size());
    const Clock::time_point start = Clock::now();
    StatusOr<TriangleMesh> mesh = DecodeBaseMesh(bytes, VertexColours::kRead);
    summary.seconds += SecondsSince(start);
    if (!mesh.ok()) return mesh.status().WithContext(path);
    summary.frames += 1;
    summary.bytes_total += bytes.size();
    summary.vertices += mesh->vertex_count();
  }
  summary.vertices /= summary.frames;
  return summary;
}

StatusOr<std::string> ReadTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return NotFoundError(path + ": cannot open");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace meshvid
