// CaptureSequence: the encoder's input, K views x M frames of range meshes each with its own
// topology. The one module that reads captures; every tool and the encoder use it.
#ifndef MESHVID_TOOLS_IO_CAPTURE_H_
#define MESHVID_TOOLS_IO_CAPTURE_H_

#include <list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "codec/common/camera.h"
#include "codec/common/mesh.h"
#include "format/status.h"
#include "tools/io/range_grid.h"

namespace meshvid {

/// One view (sensor) of the rig.
struct CaptureView {
  std::string name;
  ViewCalibration calibration;
  /// For 16-bit PNG depth images: metres (or capture units) per depth unit.
  double depth_scale = 0.001;
};

/// How a capture is described on disk; see Open().
struct CaptureInfo {
  double frame_rate = 25.0;
  std::string units = "m";
  std::vector<CaptureView> views;
  int frame_count = 0;
  /// True if the view files hold camera-frame coordinates, mapped to the world with each
  /// view's extrinsics when loaded; false if they are already in world coordinates.
  bool camera_coordinates = false;
  RangeGridMeshing meshing;  ///< the depth-jump rule used for depth images
};

/// A capture, read lazily: only the files of the frames asked for are opened.
class CaptureSequence {
 public:
  /// Opens a capture from one of:
  ///  - a `manifest.json` (see spec/capture-manifest.md);
  ///  - a file pattern with `{frame}` and `{view}` placeholders (`cap/f{frame:04}_v{view}.ply`),
  ///    views 0..K-1 and frames numbered contiguously from the smallest present; every frame
  ///    must have the same views;
  ///  - a Stanford `.conf` file (`bmesh FILE tx ty tz qi qj qk qr` lines): one frame, one view
  ///    per scan, each posed by its line.
  /// View files may be PLY, OBJ, or 16-bit PNG depth images (which need intrinsics).
  /// Checks that every file exists (CheckViewFiles); fails with a message naming the file
  /// otherwise.
  static StatusOr<std::unique_ptr<CaptureSequence>> Open(const std::string& spec);
  /// As Open, but checks no view file: for a caller that reads some frames and checks only
  /// theirs.
  static StatusOr<std::unique_ptr<CaptureSequence>> OpenWithoutChecking(const std::string& spec);

  /// Fails (not found) if a view file of frames [first_frame, end_frame) is missing, saying
  /// how many are and naming the first.
  Status CheckViewFiles(int first_frame, int end_frame) const;

  const CaptureInfo& info() const { return info_; }
  int frame_count() const { return info_.frame_count; }
  int view_count() const { return static_cast<int>(info_.views.size()); }
  /// The file of view `view` at frame `frame`.
  const std::string& view_path(int frame, int view) const;
  /// The colour image beside the depth image of view `view` at frame `frame`; empty for none.
  const std::string& colour_path(int frame, int view) const;
  /// True if some view file comes with a colour image (manifest `colour_frames` or
  /// `colour_pattern`).
  bool has_colour_images() const { return !colour_paths_.empty(); }
  /// Loads one view's mesh in world coordinates, with per-vertex colours where the view's
  /// file or colour image gives them; validated.
  StatusOr<TriangleMesh> LoadView(int frame, int view) const;
  /// Loads all views of a frame, in view order.
  StatusOr<std::vector<TriangleMesh>> LoadFrame(int frame) const;
  /// View `view`'s calibration with the camera posed in the world its loaded meshes are in
  /// (a Stanford .conf line's pose applied after the extrinsics, as LoadView does).
  ViewCalibration view_camera(int view) const;
  /// Every view's view_camera, in view order; empty when none of them can project (a
  /// capture without calibration).
  std::vector<ViewCalibration> view_cameras() const;

 private:
  friend class CaptureSequenceBuilder;
  std::string source_;  ///< the manifest, pattern or .conf, as messages name it
  CaptureInfo info_;
  /// Per frame, per view: file path; and per view an extra pose (Stanford .conf), applied
  /// after the extrinsics.
  std::vector<std::vector<std::string>> paths_;
  /// Per frame, per view: the colour image beside a depth image ("" for none); empty when
  /// no view has one.
  std::vector<std::vector<std::string>> colour_paths_;
  std::vector<Eigen::Isometry3d> view_poses_;
};

/// A sliding window over a capture: keeps at most `capacity` frames loaded, dropping the
/// least recently used, so long captures never need to be in memory whole.
class CaptureWindow {
 public:
  CaptureWindow(const CaptureSequence* capture, int capacity);
  /// The views of frame t, loading it if needed. The reference stays valid until the next
  /// call that loads a frame.
  StatusOr<const std::vector<TriangleMesh>*> Get(int frame);
  int loaded_frames() const { return static_cast<int>(frames_.size()); }

 private:
  const CaptureSequence* capture_;
  int capacity_;
  std::list<std::pair<int, std::vector<TriangleMesh>>> frames_;  // most recent at the back
};

/// Writes `manifest.json` for a capture whose view files already exist (used by the
/// simulator). `paths[frame][view]` may be relative to the manifest's directory;
/// `colour_paths`, empty or shaped as `paths` ("" for a view without one), the colour images
/// beside depth images.
Status WriteCaptureManifest(const std::string& manifest_path, const CaptureInfo& info,
                            const std::vector<std::vector<std::string>>& paths,
                            const std::vector<std::vector<std::string>>& colour_paths = {});

}  // namespace meshvid

#endif  // MESHVID_TOOLS_IO_CAPTURE_H_
