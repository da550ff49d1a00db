#include "tools/io/capture_frame_source.h"

#include <utility>

namespace meshvid {

StatusOr<std::unique_ptr<CaptureFrameSource>> CaptureFrameSource::Open(const std::string& spec) {
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<CaptureSequence> capture,
                           CaptureSequence::OpenWithoutChecking(spec));
  return std::make_unique<CaptureFrameSource>(std::move(capture));
}

CaptureFrameSource::CaptureFrameSource(std::unique_ptr<CaptureSequence> capture)
    : capture_(std::move(capture)), window_(capture_.get(), kCachedFrames) {}

StatusOr<std::vector<TriangleMesh>> CaptureFrameSource::LoadFrame(int frame) const {
  MESHVID_ASSIGN_OR_RETURN(const std::vector<TriangleMesh>* views, window_.Get(frame));
  return *views;
}

std::vector<ViewCalibration> CaptureFrameSource::view_cameras() const {
  return capture_->view_cameras();
}

}  // namespace meshvid
