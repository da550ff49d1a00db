#include "codec/common/video_codec.h"

namespace meshvid {

std::string_view VideoCodecName(VideoCodec codec) {
  switch (codec) {
    case VideoCodec::kHevc: return "hevc";
    case VideoCodec::kAv1: return "av1";
    case VideoCodec::kFfv1: return "ffv1";
  }
  return "unknown";
}

std::optional<VideoCodec> ParseVideoCodec(std::string_view name) {
  for (VideoCodec codec : {VideoCodec::kHevc, VideoCodec::kAv1, VideoCodec::kFfv1}) {
    if (name == VideoCodecName(codec)) return codec;
  }
  return std::nullopt;
}

}  // namespace meshvid
