// CaptureFrameSource: a capture on disk (CaptureSequence) as the encoder's FrameSource.
#ifndef MESHVID_TOOLS_IO_CAPTURE_FRAME_SOURCE_H_
#define MESHVID_TOOLS_IO_CAPTURE_FRAME_SOURCE_H_

#include <memory>
#include <string>
#include <vector>

#include "codec/enc/frame_source.h"
#include "tools/io/capture.h"

namespace meshvid {

/// The frames of a capture on disk, parsed on demand. The encoder reads a frame several times
/// (its proxy, a key group's base, its detail): the last kCachedFrames frames stay parsed
/// (CaptureWindow), so a short key group is analysed and detailed without parsing again.
class CaptureFrameSource : public FrameSource {
 public:
  /// Parsed frames kept (samba's 3 views at 640x480: about 15 MB a frame).
  static constexpr int kCachedFrames = 12;

  /// Opens a capture as CaptureSequence::OpenWithoutChecking does (a manifest.json, a file
  /// pattern with {frame} and {view}, or a Stanford .conf): the caller checks the view files
  /// of the frames it reads (capture().CheckViewFiles).
  static StatusOr<std::unique_ptr<CaptureFrameSource>> Open(const std::string& spec);
  /// Serves the frames of an opened capture.
  explicit CaptureFrameSource(std::unique_ptr<CaptureSequence> capture);

  /// The capture read (its views' calibration, units, file names).
  const CaptureSequence& capture() const { return *capture_; }
  int frame_count() const override { return capture_->frame_count(); }
  int view_count() const override { return capture_->view_count(); }
  double frame_rate() const override { return capture_->info().frame_rate; }
  /// The views of `frame`, parsed from their files unless among the last kCachedFrames.
  StatusOr<std::vector<TriangleMesh>> LoadFrame(int frame) const override;
  /// The views' calibration, posed as their meshes are loaded (a Stanford .conf's poses
  /// included); empty when no view can project (ViewCalibration::CanProject, what
  /// SeenFreeSpace needs).
  std::vector<ViewCalibration> view_cameras() const override;

 private:
  std::unique_ptr<CaptureSequence> capture_;
  mutable CaptureWindow window_;
};

}  // namespace meshvid

#endif  // MESHVID_TOOLS_IO_CAPTURE_FRAME_SOURCE_H_
