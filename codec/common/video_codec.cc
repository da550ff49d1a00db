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

namespace {
constexpr VideoCodec kAllCodecs[] = {VideoCodec::kHevc, VideoCodec::kAv1, VideoCodec::kFfv1};
}  // namespace

std::optional<VideoCodec> ParseVideoCodec(std::string_view name) {
  for (VideoCodec codec : kAllCodecs) {
    if (name == VideoCodecName(codec)) return codec;
  }
  return std::nullopt;
}

std::string_view VideoCodecTag(VideoCodec codec) {
  // AV1's tag is its ISO BMFF sample entry; the others' names are already four characters.
  return codec == VideoCodec::kAv1 ? "av01" : VideoCodecName(codec);
}

std::optional<VideoCodec> ParseVideoCodecTag(std::string_view tag) {
  for (VideoCodec codec : kAllCodecs) {
    if (tag == VideoCodecTag(codec)) return codec;
  }
  return std::nullopt;
}

}  // namespace meshvid
