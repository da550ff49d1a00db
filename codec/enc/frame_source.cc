#include "codec/enc/frame_source.h"

#include <cmath>
#include <string>

namespace meshvid {

StatusOr<MemoryFrameSource> MemoryFrameSource::Create(
    std::vector<std::vector<TriangleMesh>> frames, double frame_rate) {
  if (!(frame_rate > 0) || !std::isfinite(frame_rate)) {
    return InvalidArgumentError("frame_rate must be a positive number");
  }
  if (frames.empty()) return InvalidArgumentError("frames: the capture has no frame");
  const std::size_t views = frames.front().size();
  if (views == 0) return InvalidArgumentError("frames[0] has no view");
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (frames[f].size() != views) {
      return InvalidArgumentError("frames[" + std::to_string(f) + "] has " +
                                  std::to_string(frames[f].size()) + " views, frames[0] " +
                                  std::to_string(views) + "; every frame needs the same views");
    }
    for (std::size_t v = 0; v < views; ++v) {
      const std::string name = "frames[" + std::to_string(f) + "][" + std::to_string(v) + "]";
      const Status valid = ValidateMesh(frames[f][v], name);
      if (!valid.ok()) return InvalidArgumentError(valid.message());
    }
  }
  return MemoryFrameSource(std::move(frames), frame_rate);
}

StatusOr<std::vector<TriangleMesh>> MemoryFrameSource::LoadFrame(int frame) const {
  if (frame < 0 || frame >= frame_count()) {
    return InvalidArgumentError("frame " + std::to_string(frame) + " is outside 0.." +
                                std::to_string(frame_count() - 1));
  }
  return frames_[frame];
}

}  // namespace meshvid
