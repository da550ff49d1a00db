// The capture manifest (manifest.json, spec/capture-manifest.md): reading and writing.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "format/output_file.h"
#include "tools/io/capture.h"
#include "tools/io/capture_builder.h"
#include "tools/io/file_pattern.h"

namespace meshvid {
namespace {

using Json = nlohmann::json;

constexpr char kFormatName[] = "meshvid-capture";
constexpr int kFormatVersion = 1;
/// The highest frame_rate a manifest may state: the .mvid writer's limit (frames per second).
constexpr double kMaxFrameRate = 1000;

/// Shortest decimal text that reads back as the same float.
std::string FloatText(float value) {
  std::ostringstream text;
  text << std::setprecision(9) << value;
  for (int precision = 1; precision <= 9; ++precision) {
    std::ostringstream shorter;
    shorter << std::setprecision(precision) << value;
    if (std::stof(shorter.str()) == value) return shorter.str();
  }
  return text.str();
}

/// Reads one manifest, producing errors "MANIFEST: JSON.PATH what is wrong".
class ManifestReader {
 public:
  explicit ManifestReader(std::string manifest) : manifest_(std::move(manifest)) {}

  Status Error(const std::string& json_path, const std::string& what) const {
    return CorruptError(manifest_ + ": " + json_path + " " + what);
  }

  /// Fails if `object` (at `json_path`) has a key not in `known`, to catch misspellings.
  Status CheckKeys(const Json& object, const std::string& json_path,
                   std::initializer_list<const char*> known) const {
    for (const auto& [key, value] : object.items()) {
      bool found = false;
      std::string list;
      for (const char* name : known) {
        found = found || key == name;
        list += (list.empty() ? "" : ", ") + std::string(name);
      }
      if (!found) {
        return Error(json_path.empty() ? key : json_path + "." + key,
                     "is not a known field (known: " + list + ")");
      }
    }
    return Status::Ok();
  }

  /// A number at `json_path`; `positive` requires > 0. Absent: `fallback` if given.
  StatusOr<double> Number(const Json& object, const std::string& key, const std::string& json_path,
                          bool positive, std::optional<double> fallback = std::nullopt) const {
    if (!object.contains(key)) {
      if (fallback) return *fallback;
      return Error(json_path, "is missing");
    }
    const Json& value = object.at(key);
    if (!value.is_number()) return Error(json_path, "must be a number");
    const double number = value.get<double>();
    if (!std::isfinite(number)) return Error(json_path, "must be finite");
    if (positive && !(number > 0)) return Error(json_path, "must be > 0");
    return number;
  }

  /// A positive integer at `json_path`.
  StatusOr<int> PositiveInt(const Json& object, const std::string& key,
                            const std::string& json_path) const {
    if (!object.contains(key)) return Error(json_path, "is missing");
    const Json& value = object.at(key);
    if (!value.is_number_integer() || value.get<long long>() <= 0 ||
        value.get<long long>() > 1'000'000'000) {
      return Error(json_path, "must be a positive integer");
    }
    return value.get<int>();
  }

  StatusOr<PinholeIntrinsics> Intrinsics(const Json& json, const std::string& at) const {
    if (!json.is_object()) return Error(at, "must be an object {width, height, fx, fy, cx, cy}");
    MESHVID_RETURN_IF_ERROR(CheckKeys(json, at, {"width", "height", "fx", "fy", "cx", "cy"}));
    PinholeIntrinsics k;
    MESHVID_ASSIGN_OR_RETURN(k.width, PositiveInt(json, "width", at + ".width"));
    MESHVID_ASSIGN_OR_RETURN(k.height, PositiveInt(json, "height", at + ".height"));
    MESHVID_ASSIGN_OR_RETURN(k.fx, Number(json, "fx", at + ".fx", true));
    MESHVID_ASSIGN_OR_RETURN(k.fy, Number(json, "fy", at + ".fy", true));
    MESHVID_ASSIGN_OR_RETURN(k.cx, Number(json, "cx", at + ".cx", false));
    MESHVID_ASSIGN_OR_RETURN(k.cy, Number(json, "cy", at + ".cy", false));
    return k;
  }

  StatusOr<Eigen::Isometry3d> RigidTransform(const Json& json, const std::string& at) const {
    if (!json.is_array() || json.size() != 16) {
      return Error(at, "must be an array of 16 numbers (a row-major 4x4 matrix)");
    }
    Eigen::Matrix4d matrix;
    for (int i = 0; i < 16; ++i) {
      const Json& value = json[i];
      if (!value.is_number() || !std::isfinite(value.get<double>())) {
        return Error(at + "[" + std::to_string(i) + "]", "must be a finite number");
      }
      matrix(i / 4, i % 4) = value.get<double>();
    }
    if (!matrix.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-9)) {
      return Error(at, "must end with the row 0 0 0 1");
    }
    const Eigen::Matrix3d rotation = matrix.topLeftCorner<3, 3>();
    if (!(rotation.transpose() * rotation).isApprox(Eigen::Matrix3d::Identity(), 1e-5) ||
        rotation.determinant() < 0) {
      return Error(at, "is not a rigid transform: its upper-left 3x3 must be a rotation");
    }
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = rotation;
    pose.translation() = matrix.topRightCorner<3, 1>();
    return pose;
  }

  StatusOr<CaptureView> View(const Json& json, int index) const {
    const std::string at = "views[" + std::to_string(index) + "]";
    if (!json.is_object()) return Error(at, "must be an object");
    MESHVID_RETURN_IF_ERROR(
        CheckKeys(json, at, {"name", "intrinsics", "world_from_camera", "depth_scale"}));
    CaptureView view;
    view.name = DefaultViewName(index);
    if (json.contains("name")) {
      if (!json["name"].is_string()) return Error(at + ".name", "must be a string");
      view.name = json["name"].get<std::string>();
    }
    if (json.contains("intrinsics")) {
      MESHVID_ASSIGN_OR_RETURN(view.calibration.intrinsics,
                               Intrinsics(json["intrinsics"], at + ".intrinsics"));
    }
    if (json.contains("world_from_camera")) {
      MESHVID_ASSIGN_OR_RETURN(
          view.calibration.world_from_camera,
          RigidTransform(json["world_from_camera"], at + ".world_from_camera"));
      view.calibration.has_extrinsics = true;
    }
    MESHVID_ASSIGN_OR_RETURN(view.depth_scale,
                             Number(json, "depth_scale", at + ".depth_scale", true, 0.001));
    return view;
  }

  /// The per-frame file lists, from "frames" or "pattern" + "frame_count".
  StatusOr<std::vector<std::vector<std::string>>> Paths(const Json& root, int view_count) const {
    std::vector<std::vector<std::string>> paths;
    if (root.contains("frames") == root.contains("pattern")) {
      return Error("frames", "or pattern (with frame_count) must be given, and not both");
    }
    if (root.contains("frames")) {
      const Json& frames = root["frames"];
      if (!frames.is_array() || frames.empty()) {
        return Error("frames", "must be a non-empty array of per-frame file lists");
      }
      for (std::size_t f = 0; f < frames.size(); ++f) {
        const std::string at = "frames[" + std::to_string(f) + "]";
        if (!frames[f].is_array()) return Error(at, "must be an array of file names");
        if (static_cast<int>(frames[f].size()) != view_count) {
          return Error(at, "has " + std::to_string(frames[f].size()) + " views, expected " +
                               std::to_string(view_count));
        }
        std::vector<std::string> row;
        for (std::size_t v = 0; v < frames[f].size(); ++v) {
          if (!frames[f][v].is_string() || frames[f][v].get<std::string>().empty()) {
            return Error(at + "[" + std::to_string(v) + "]", "must be a file name");
          }
          row.push_back(ResolveBesides(manifest_, frames[f][v].get<std::string>()));
        }
        paths.push_back(std::move(row));
      }
      if (root.contains("frame_count") || root.contains("first_frame")) {
        return Error("frame_count", "and first_frame go only with pattern, not with frames");
      }
      return paths;
    }
    if (!root["pattern"].is_string()) return Error("pattern", "must be a string");
    const std::string text = ResolveBesides(manifest_, root["pattern"].get<std::string>());
    StatusOr<FilePattern> pattern = FilePattern::Parse(text);
    if (!pattern.ok()) return Error("pattern", "is invalid: " + pattern.status().message());
    if (!pattern->has_view() && view_count > 1) {
      return Error("pattern", "has no {view} placeholder but the capture has " +
                                  std::to_string(view_count) + " views");
    }
    MESHVID_ASSIGN_OR_RETURN(const int frame_count,
                             PositiveInt(root, "frame_count", "frame_count"));
    if (!pattern->has_frame() && frame_count > 1) {
      return Error("pattern",
                   "has no {frame} placeholder but frame_count is " + std::to_string(frame_count));
    }
    int first_frame = 0;
    if (root.contains("first_frame")) {
      const Json& value = root["first_frame"];
      if (!value.is_number_integer() || value.get<long long>() < 0 ||
          value.get<long long>() > 1'000'000'000) {
        return Error("first_frame", "must be a non-negative integer");
      }
      first_frame = value.get<int>();
    }
    // The count comes from the file: before expanding it into paths (up to 10^9 frames),
    // the last frame's files must exist, so the paths are justified by what is on disk.
    for (int v = 0; v < view_count; ++v) {
      const std::string last = pattern->Expand(first_frame + frame_count - 1, v);
      std::error_code error;
      if (!std::filesystem::exists(last, error)) {
        return Error("frame_count", "is " + std::to_string(frame_count) +
                                        " but the last frame's view file " + last +
                                        " does not exist");
      }
    }
    for (int f = 0; f < frame_count; ++f) {
      std::vector<std::string> row;
      for (int v = 0; v < view_count; ++v) row.push_back(pattern->Expand(first_frame + f, v));
      paths.push_back(std::move(row));
    }
    return paths;
  }

  /// The colour images beside depth images: "colour_frames" (shaped as "frames", null for a
  /// view without one) or "colour_pattern" (expanded as "pattern" is); none without either.
  StatusOr<std::vector<std::vector<std::string>>> ColourPaths(const Json& root, int view_count,
                                                              int frame_count) const {
    std::vector<std::vector<std::string>> paths;
    if (root.contains("colour_frames") && root.contains("colour_pattern")) {
      return Error("colour_frames", "and colour_pattern must not both be given");
    }
    if (root.contains("colour_frames")) {
      if (!root.contains("frames")) {
        return Error("colour_frames", "goes with frames; with pattern, give colour_pattern");
      }
      const Json& frames = root["colour_frames"];
      if (!frames.is_array() || static_cast<int>(frames.size()) != frame_count) {
        return Error("colour_frames",
                     "must be an array of per-frame colour image lists, one "
                     "for each of the " +
                         std::to_string(frame_count) + " frames");
      }
      for (std::size_t f = 0; f < frames.size(); ++f) {
        const std::string at = "colour_frames[" + std::to_string(f) + "]";
        if (!frames[f].is_array() || static_cast<int>(frames[f].size()) != view_count) {
          return Error(at, "must be an array of " + std::to_string(view_count) +
                               " colour image names (null for a view without one)");
        }
        std::vector<std::string> row;
        for (std::size_t v = 0; v < frames[f].size(); ++v) {
          const Json& name = frames[f][v];
          if (name.is_null()) {
            row.emplace_back();
          } else if (name.is_string() && !name.get<std::string>().empty()) {
            row.push_back(ResolveBesides(manifest_, name.get<std::string>()));
          } else {
            return Error(at + "[" + std::to_string(v) + "]", "must be a file name or null");
          }
        }
        paths.push_back(std::move(row));
      }
    } else if (root.contains("colour_pattern")) {
      if (!root.contains("pattern")) {
        return Error("colour_pattern", "goes with pattern; with frames, give colour_frames");
      }
      if (!root["colour_pattern"].is_string()) return Error("colour_pattern", "must be a string");
      StatusOr<FilePattern> pattern =
          FilePattern::Parse(ResolveBesides(manifest_, root["colour_pattern"].get<std::string>()));
      if (!pattern.ok()) {
        return Error("colour_pattern", "is invalid: " + pattern.status().message());
      }
      if (!pattern->has_view() && view_count > 1) {
        return Error("colour_pattern", "has no {view} placeholder but the capture has " +
                                           std::to_string(view_count) + " views");
      }
      if (!pattern->has_frame() && frame_count > 1) {
        return Error("colour_pattern", "has no {frame} placeholder but the capture has " +
                                           std::to_string(frame_count) + " frames");
      }
      const int first_frame = root.value("first_frame", 0);  // checked with pattern
      for (int f = 0; f < frame_count; ++f) {
        std::vector<std::string> row;
        for (int v = 0; v < view_count; ++v) row.push_back(pattern->Expand(first_frame + f, v));
        paths.push_back(std::move(row));
      }
    }
    return paths;
  }

  StatusOr<std::unique_ptr<CaptureSequence>> Read() const {
    std::ifstream in(manifest_);
    if (!in) return NotFoundError(manifest_ + ": cannot open the capture manifest");
    Json root = Json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (root.is_discarded()) return CorruptError(manifest_ + ": not valid JSON");
    if (!root.is_object()) return Error("(top level)", "must be a JSON object");
    MESHVID_RETURN_IF_ERROR(
        CheckKeys(root, "",
                  {"format", "version", "frame_rate", "units", "coordinates", "depth_jump_ratio",
                   "views", "frames", "pattern", "frame_count", "first_frame", "colour_frames",
                   "colour_pattern", "source"}));
    if (!root.contains("format") || root["format"] != kFormatName) {
      return Error("format", std::string("must be \"") + kFormatName + "\"");
    }
    if (!root.contains("version") || !root["version"].is_number_integer()) {
      return Error("version", "must be an integer");
    }
    if (root["version"].get<long long>() != kFormatVersion) {
      return UnsupportedError(manifest_ + ": version " + root["version"].dump() +
                              " is not supported (this meshvid reads version 1)");
    }
    CaptureInfo info;
    MESHVID_ASSIGN_OR_RETURN(info.frame_rate, Number(root, "frame_rate", "frame_rate", true, 25.0));
    if (info.frame_rate > kMaxFrameRate) {
      return Error("frame_rate", "must be at most " + std::to_string(int(kMaxFrameRate)) +
                                     " (frames per second)");
    }
    if (root.contains("units")) {
      if (!root["units"].is_string()) return Error("units", "must be a string");
      info.units = root["units"].get<std::string>();
    }
    if (root.contains("coordinates")) {
      const Json& value = root["coordinates"];
      if (value != "world" && value != "camera") {
        return Error("coordinates", "must be \"world\" or \"camera\"");
      }
      info.camera_coordinates = value == "camera";
    }
    MESHVID_ASSIGN_OR_RETURN(const double jump,
                             Number(root, "depth_jump_ratio", "depth_jump_ratio", true,
                                    RangeGridMeshing().max_depth_jump_ratio));
    info.meshing.max_depth_jump_ratio = static_cast<float>(jump);
    if (!root.contains("views") || !root["views"].is_array() || root["views"].empty()) {
      return Error("views", "must be a non-empty array of view objects");
    }
    for (std::size_t v = 0; v < root["views"].size(); ++v) {
      MESHVID_ASSIGN_OR_RETURN(CaptureView view, View(root["views"][v], static_cast<int>(v)));
      if (info.camera_coordinates && !view.calibration.has_extrinsics) {
        return Error("views[" + std::to_string(v) + "].world_from_camera",
                     "is required when coordinates is \"camera\"");
      }
      info.views.push_back(std::move(view));
    }
    const int view_count = static_cast<int>(info.views.size());
    MESHVID_ASSIGN_OR_RETURN(auto paths, Paths(root, view_count));
    MESHVID_ASSIGN_OR_RETURN(auto colour_paths,
                             ColourPaths(root, view_count, static_cast<int>(paths.size())));
    return CaptureSequenceBuilder::Make(manifest_, std::move(info), std::move(paths), {},
                                        std::move(colour_paths));
  }

 private:
  std::string manifest_;
};

}  // namespace

StatusOr<std::unique_ptr<CaptureSequence>> CaptureSequenceBuilder::FromManifest(
    const std::string& path) {
  return ManifestReader(path).Read();
}

Status WriteCaptureManifest(const std::string& manifest_path, const CaptureInfo& info,
                            const std::vector<std::vector<std::string>>& paths,
                            const std::vector<std::vector<std::string>>& colour_paths) {
  if (info.views.empty()) return InvalidArgumentError(manifest_path + ": no view to write");
  if (paths.empty()) return InvalidArgumentError(manifest_path + ": no frame to write");
  Json root;
  root["format"] = kFormatName;
  root["version"] = kFormatVersion;
  root["frame_rate"] = info.frame_rate;
  root["units"] = info.units;
  root["coordinates"] = info.camera_coordinates ? "camera" : "world";
  // The float ratio written with float precision, so 0.03f is written as 0.03.
  root["depth_jump_ratio"] = std::stod(FloatText(info.meshing.max_depth_jump_ratio));
  Json views = Json::array();
  for (const CaptureView& view : info.views) {
    Json entry;
    entry["name"] = view.name;
    if (view.calibration.intrinsics) {
      const PinholeIntrinsics& k = *view.calibration.intrinsics;
      entry["intrinsics"] = {{"width", k.width}, {"height", k.height}, {"fx", k.fx},
                             {"fy", k.fy},       {"cx", k.cx},         {"cy", k.cy}};
    }
    if (view.calibration.has_extrinsics) {
      Json matrix = Json::array();
      const Eigen::Matrix4d m = view.calibration.world_from_camera.matrix();
      for (int i = 0; i < 16; ++i) matrix.push_back(m(i / 4, i % 4));
      entry["world_from_camera"] = matrix;
    }
    entry["depth_scale"] = view.depth_scale;
    views.push_back(entry);
  }
  root["views"] = views;
  Json frames = Json::array();
  for (std::size_t f = 0; f < paths.size(); ++f) {
    if (paths[f].size() != info.views.size()) {
      return InvalidArgumentError(manifest_path + ": frame " + std::to_string(f) + " has " +
                                  std::to_string(paths[f].size()) + " files but the capture has " +
                                  std::to_string(info.views.size()) + " views");
    }
    frames.push_back(paths[f]);
  }
  root["frames"] = frames;
  if (!colour_paths.empty()) {
    if (colour_paths.size() != paths.size()) {
      return InvalidArgumentError(manifest_path + ": colour images for " +
                                  std::to_string(colour_paths.size()) + " frames, but " +
                                  std::to_string(paths.size()) + " frames");
    }
    Json colour_frames = Json::array();
    for (std::size_t f = 0; f < colour_paths.size(); ++f) {
      if (colour_paths[f].size() != info.views.size()) {
        return InvalidArgumentError(manifest_path + ": frame " + std::to_string(f) + " has " +
                                    std::to_string(colour_paths[f].size()) +
                                    " colour images but the capture has " +
                                    std::to_string(info.views.size()) + " views");
      }
      Json row = Json::array();
      for (const std::string& name : colour_paths[f]) {
        row.push_back(name.empty() ? Json(nullptr) : Json(name));
      }
      colour_frames.push_back(row);
    }
    root["colour_frames"] = colour_frames;
  }
  return WriteFileAtomically(manifest_path, root.dump(2) + "\n");
}

}  // namespace meshvid
