// The encoder's input: a FrameSource hands out the views of one frame at a time. The library
// ships MemoryFrameSource (frames held in memory); tools/io/capture_frame_source.h reads a
// capture on disk.
#ifndef MESHVID_CODEC_ENC_FRAME_SOURCE_H_
#define MESHVID_CODEC_ENC_FRAME_SOURCE_H_

#include <utility>
#include <vector>

#include "codec/common/camera.h"
#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// The encoder's input: K views x M frames of range meshes in world coordinates. Frames are
/// loaded on demand, a window at a time, so a long capture never has to be in memory whole.
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual int frame_count() const = 0;     ///< frames M
  virtual int view_count() const = 0;      ///< views K, the same in every frame
  virtual double frame_rate() const = 0;   ///< frames per second, stored in the file
  /// All views of frame `frame` (0-based), in view order. May be called from one thread only.
  virtual StatusOr<std::vector<TriangleMesh>> LoadFrame(int frame) const = 0;
  /// The views' cameras in view order, where known (empty: none). With them the encoder knows
  /// the space each view saw through and ends a fused base's open edges there.
  virtual std::vector<ViewCalibration> view_cameras() const { return {}; }
};

/// A capture held in memory: `frames[frame][view]`, every frame with the same views.
class MemoryFrameSource : public FrameSource {
 public:
  /// Checks the frames: at least one, each with the same number (>= 1) of views, every mesh
  /// valid (TriangleMesh::Validate); `frame_rate` > 0. Fails with kInvalidArgument naming the
  /// frame and view otherwise.
  static StatusOr<MemoryFrameSource> Create(std::vector<std::vector<TriangleMesh>> frames,
                                            double frame_rate = 25.0);

  int frame_count() const override { return static_cast<int>(frames_.size()); }
  int view_count() const override { return static_cast<int>(frames_.front().size()); }
  double frame_rate() const override { return frame_rate_; }
  /// A copy of frame `frame`'s views; kInvalidArgument outside 0..frame_count()-1.
  StatusOr<std::vector<TriangleMesh>> LoadFrame(int frame) const override;
  std::vector<ViewCalibration> view_cameras() const override { return cameras_; }
  /// Gives the views' cameras (one per view, in view order; see FrameSource::view_cameras).
  void set_view_cameras(std::vector<ViewCalibration> cameras) { cameras_ = std::move(cameras); }

 private:
  MemoryFrameSource(std::vector<std::vector<TriangleMesh>> frames, double frame_rate)
      : frames_(std::move(frames)), frame_rate_(frame_rate) {}
  std::vector<std::vector<TriangleMesh>> frames_;
  double frame_rate_;
  std::vector<ViewCalibration> cameras_;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_FRAME_SOURCE_H_
