// CaptureSequence: opening captures from patterns and Stanford .conf files, loading views,
// and the CaptureWindow cache. The manifest reader/writer is in capture_manifest.cc.
#include "tools/io/capture.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <system_error>

#include "tools/io/capture_builder.h"
#include "tools/io/depth_image.h"
#include "tools/io/file_pattern.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

namespace fs = std::filesystem;

std::string LowerExtension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

/// "{0,2}" from a set of view numbers.
std::string FormatViews(const std::set<int>& views) {
  std::string text = "{";
  for (int view : views) {
    if (text.size() > 1) text += ',';
    text += std::to_string(view);
  }
  return text + "}";
}

}  // namespace

std::string DefaultViewName(int index) {
  std::string name = "v";
  name += std::to_string(index);
  return name;
}

bool IsDepthImagePath(const std::string& path) { return LowerExtension(path) == ".png"; }

std::string ResolveBesides(const std::string& anchor_file, const std::string& relative) {
  const fs::path path(relative);
  if (path.is_absolute()) return relative;
  const fs::path folder = fs::path(anchor_file).parent_path();
  return folder.empty() ? relative : (folder / path).string();
}

StatusOr<std::unique_ptr<CaptureSequence>> CaptureSequence::Open(const std::string& spec) {
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<CaptureSequence> capture, OpenWithoutChecking(spec));
  MESHVID_RETURN_IF_ERROR(capture->CheckViewFiles(0, capture->frame_count()));
  return capture;
}

Status CaptureSequence::CheckViewFiles(int first_frame, int end_frame) const {
  first_frame = std::max(first_frame, 0);
  end_frame = std::min(end_frame, frame_count());
  int missing = 0, checked = 0;
  std::string first_missing;
  std::error_code error;
  for (int frame = first_frame; frame < end_frame; ++frame) {
    for (int view = 0; view < view_count(); ++view) {
      const std::string& colour = colour_path(frame, view);
      for (const std::string* path : {&paths_[frame][view], &colour}) {
        if (path->empty()) continue;
        ++checked;
        if (fs::is_regular_file(*path, error)) continue;
        if (missing++ == 0) {
          first_missing = *path + " (frame " + std::to_string(frame) + ", view " +
                          std::to_string(view) + (path == &colour ? ", its colour image)" : ")");
        }
      }
    }
  }
  if (missing == 0) return Status::Ok();
  const bool every_frame = first_frame == 0 && end_frame == frame_count();
  return NotFoundError(source_ + ": " + std::to_string(missing) + " of the " +
                       std::to_string(checked) + " view files" +
                       (every_frame ? std::string()
                                    : " of frames " + std::to_string(first_frame) + ".." +
                                          std::to_string(end_frame - 1)) +
                       " are missing, the first is " + first_missing);
}

StatusOr<std::unique_ptr<CaptureSequence>> CaptureSequence::OpenWithoutChecking(
    const std::string& spec) {
  if (FilePattern::LooksLikePattern(spec)) return CaptureSequenceBuilder::FromPattern(spec);
  const std::string extension = LowerExtension(spec);
  if (extension == ".json") return CaptureSequenceBuilder::FromManifest(spec);
  if (extension == ".conf") return CaptureSequenceBuilder::FromConf(spec);
  std::error_code error;
  if (fs::is_directory(spec, error) && fs::exists(fs::path(spec) / "manifest.json", error)) {
    return CaptureSequenceBuilder::FromManifest((fs::path(spec) / "manifest.json").string());
  }
  return InvalidArgumentError(
      "'" + spec +
      "' is not a capture: expected a manifest.json (or a folder holding one), a "
      "file pattern such as cap/f{frame:04}_v{view}.ply, or a Stanford .conf file");
}

StatusOr<std::unique_ptr<CaptureSequence>> CaptureSequenceBuilder::Make(
    const std::string& source, CaptureInfo info, std::vector<std::vector<std::string>> paths,
    std::vector<Eigen::Isometry3d> poses, std::vector<std::vector<std::string>> colour_paths) {
  const int view_count = static_cast<int>(info.views.size());
  if (view_count == 0) return InvalidArgumentError(source + ": the capture has no view");
  if (paths.empty()) return InvalidArgumentError(source + ": the capture has no frame");
  if (poses.empty()) poses.assign(view_count, Eigen::Isometry3d::Identity());
  for (int view = 0; view < view_count; ++view) {
    for (const auto& frame_paths : paths) {
      if (IsDepthImagePath(frame_paths[view]) && !info.views[view].calibration.intrinsics) {
        return InvalidArgumentError(source + ": view " + std::to_string(view) + " ('" +
                                    info.views[view].name + "') has depth images (" +
                                    frame_paths[view] + ") but no intrinsics; give views[" +
                                    std::to_string(view) + "].intrinsics in a manifest");
      }
    }
  }
  if (!colour_paths.empty() && colour_paths.size() != paths.size()) {
    return InvalidArgumentError(source + ": colour images for " +
                                std::to_string(colour_paths.size()) + " frames, but " +
                                std::to_string(paths.size()) + " frames");
  }
  for (std::size_t frame = 0; frame < colour_paths.size(); ++frame) {
    for (int view = 0; view < view_count; ++view) {
      const std::string& colour = colour_paths[frame].at(view);
      if (!colour.empty() && !IsDepthImagePath(paths[frame][view])) {
        return InvalidArgumentError(
            source + ": colour image " + colour + " goes with " + paths[frame][view] +
            ", which is not a PNG depth image; a mesh file carries its own vertex colours");
      }
    }
  }
  const bool any_colour =
      std::any_of(colour_paths.begin(), colour_paths.end(), [](const auto& row) {
        return std::any_of(row.begin(), row.end(), [](const std::string& p) { return !p.empty(); });
      });
  if (!any_colour) colour_paths.clear();
  auto capture = std::make_unique<CaptureSequence>();
  capture->source_ = source;
  info.frame_count = static_cast<int>(paths.size());
  capture->info_ = std::move(info);
  capture->paths_ = std::move(paths);
  capture->colour_paths_ = std::move(colour_paths);
  capture->view_poses_ = std::move(poses);
  return capture;
}

StatusOr<std::unique_ptr<CaptureSequence>> CaptureSequenceBuilder::FromPattern(
    const std::string& spec) {
  MESHVID_ASSIGN_OR_RETURN(FilePattern pattern, FilePattern::Parse(spec));
  MESHVID_ASSIGN_OR_RETURN(auto files, pattern.Scan());
  if (files.empty()) return NotFoundError("no file matches the capture pattern '" + spec + "'");
  std::map<int, std::set<int>> views_of_frame;
  int view_count = 0;
  for (const auto& [key, path] : files) {
    views_of_frame[key.first].insert(key.second);
    view_count = std::max(view_count, key.second + 1);
  }
  const int first_frame = views_of_frame.begin()->first;
  int expected_frame = first_frame;
  std::vector<std::vector<std::string>> paths;
  for (const auto& [frame, views] : views_of_frame) {
    if (frame != expected_frame) {
      return NotFoundError("capture pattern '" + spec + "': frames must be contiguous from " +
                           std::to_string(first_frame) + ", but frame " +
                           std::to_string(expected_frame) + " is missing (no " +
                           pattern.Expand(expected_frame, 0) + ")");
    }
    if (static_cast<int>(views.size()) != view_count) {
      int missing_view = 0;
      while (views.count(missing_view) != 0) ++missing_view;
      return NotFoundError("capture pattern '" + spec +
                           "': view count differs between frames: frame " + std::to_string(frame) +
                           " has views " + FormatViews(views) + ", expected " +
                           std::to_string(view_count) + " views (missing " +
                           pattern.Expand(frame, missing_view) + ")");
    }
    std::vector<std::string> row;
    for (int view = 0; view < view_count; ++view) row.push_back(files.at({frame, view}));
    paths.push_back(std::move(row));
    ++expected_frame;
  }
  CaptureInfo info;
  for (int view = 0; view < view_count; ++view) {
    info.views.push_back(CaptureView{DefaultViewName(view), {}, 0.001});
  }
  return Make("capture pattern '" + spec + "'", std::move(info), std::move(paths), {});
}

StatusOr<std::unique_ptr<CaptureSequence>> CaptureSequenceBuilder::FromConf(
    const std::string& path) {
  std::ifstream in(path);
  if (!in) return NotFoundError(path + ": cannot open the .conf file");
  CaptureInfo info;
  std::vector<std::string> files;
  std::vector<Eigen::Isometry3d> poses;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword) || keyword[0] == '#' || keyword == "camera") continue;
    const std::string where = path + ":" + std::to_string(line_number) + ": ";
    if (keyword != "bmesh") {
      return CorruptError(where + "unknown keyword '" + keyword +
                          "' (expected 'camera' or 'bmesh FILE tx ty tz qi qj qk qr')");
    }
    std::string file;
    double t[3];
    double q[4];  // qi qj qk qr: the real part last
    if (!(words >> file >> t[0] >> t[1] >> t[2] >> q[0] >> q[1] >> q[2] >> q[3])) {
      return CorruptError(where + "expected 'bmesh FILE tx ty tz qi qj qk qr'");
    }
    const Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
    if (std::abs(rotation.norm() - 1.0) > 1e-3) {
      return CorruptError(where + "the quaternion (" + std::to_string(q[0]) + ", " +
                          std::to_string(q[1]) + ", " + std::to_string(q[2]) + ", " +
                          std::to_string(q[3]) + ") is not a unit quaternion");
    }
    // Checked on the Stanford bunny: scan points p map to the common frame as
    // conj(q) p + t, i.e. with the inverse of the Hamilton rotation of (qr; qi, qj, qk).
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = rotation.normalized().conjugate().toRotationMatrix();
    pose.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
    files.push_back(ResolveBesides(path, file));
    poses.push_back(pose);
    info.views.push_back(CaptureView{fs::path(file).stem().string(), {}, 0.001});
  }
  if (files.empty()) return CorruptError(path + ": no 'bmesh' line, so no scan to read");
  return Make(path, std::move(info), {files}, std::move(poses));
}

const std::string& CaptureSequence::view_path(int frame, int view) const {
  return paths_.at(frame).at(view);
}

const std::string& CaptureSequence::colour_path(int frame, int view) const {
  static const std::string kNone;
  return colour_paths_.empty() ? kNone : colour_paths_.at(frame).at(view);
}

StatusOr<TriangleMesh> CaptureSequence::LoadView(int frame, int view) const {
  if (frame < 0 || frame >= frame_count()) {
    return InvalidArgumentError("frame " + std::to_string(frame) +
                                " is out of range: the "
                                "capture has " +
                                std::to_string(frame_count()) + " frames");
  }
  if (view < 0 || view >= view_count()) {
    return InvalidArgumentError("view " + std::to_string(view) +
                                " is out of range: the "
                                "capture has " +
                                std::to_string(view_count()) + " views");
  }
  const std::string& path = paths_[frame][view];
  const CaptureView& capture_view = info_.views[view];
  const ViewCalibration& calibration = capture_view.calibration;
  TriangleMesh mesh;
  if (IsDepthImagePath(path)) {
    if (!calibration.intrinsics) {
      return InvalidArgumentError(path + ": a depth image needs its view's intrinsics");
    }
    MESHVID_ASSIGN_OR_RETURN(DepthImage image, ReadDepthPng(path));
    const std::string& colour_file = colour_path(frame, view);
    std::optional<ColourImage> colour;
    if (!colour_file.empty()) {
      MESHVID_ASSIGN_OR_RETURN(colour, ReadColourPng(colour_file));
    }
    MESHVID_ASSIGN_OR_RETURN(
        mesh, MeshDepthImage(image, *calibration.intrinsics, capture_view.depth_scale,
                             calibration.world_from_camera, info_.meshing, path,
                             colour ? &*colour : nullptr, colour_file));
  } else {
    StatusOr<TriangleMesh> read = ReadMesh(path);
    if (!read.ok()) {
      const Status& status = read.status();
      if (status.message().find(path) != std::string::npos) return status;
      return status.WithContext(path);
    }
    mesh = std::move(read).value();
    if (info_.camera_coordinates) {
      TransformMesh(Eigen::Affine3d(calibration.world_from_camera.matrix()), &mesh);
    }
  }
  const Eigen::Isometry3d& pose = view_poses_[view];
  if (!pose.isApprox(Eigen::Isometry3d::Identity(), 0.0)) {
    TransformMesh(Eigen::Affine3d(pose.matrix()), &mesh);
  }
  MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, path));
  return mesh;
}

ViewCalibration CaptureSequence::view_camera(int view) const {
  ViewCalibration camera = info_.views[view].calibration;
  camera.world_from_camera = view_poses_[view] * camera.world_from_camera;
  return camera;
}

std::vector<ViewCalibration> CaptureSequence::view_cameras() const {
  std::vector<ViewCalibration> cameras;
  bool any_usable = false;
  for (int view = 0; view < view_count(); ++view) {
    cameras.push_back(view_camera(view));
    any_usable |= cameras.back().CanProject();
  }
  if (!any_usable) cameras.clear();
  return cameras;
}

StatusOr<std::vector<TriangleMesh>> CaptureSequence::LoadFrame(int frame) const {
  std::vector<TriangleMesh> meshes;
  meshes.reserve(view_count());
  for (int view = 0; view < view_count(); ++view) {
    MESHVID_ASSIGN_OR_RETURN(TriangleMesh mesh, LoadView(frame, view));
    meshes.push_back(std::move(mesh));
  }
  return meshes;
}

CaptureWindow::CaptureWindow(const CaptureSequence* capture, int capacity)
    : capture_(capture), capacity_(std::max(1, capacity)) {}

StatusOr<const std::vector<TriangleMesh>*> CaptureWindow::Get(int frame) {
  // A hit moves the frame to the back (most recently used); splicing a list node keeps
  // every reference handed out valid.
  for (auto it = frames_.begin(); it != frames_.end(); ++it) {
    if (it->first == frame) {
      frames_.splice(frames_.end(), frames_, it);
      return &frames_.back().second;
    }
  }
  MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> meshes, capture_->LoadFrame(frame));
  // Evict before inserting so the window never exceeds its capacity, even momentarily.
  while (static_cast<int>(frames_.size()) >= capacity_) frames_.pop_front();
  frames_.emplace_back(frame, std::move(meshes));
  return &frames_.back().second;
}

}  // namespace meshvid
