#include "codec/dec/stream_header.h"

#include <optional>

#include "codec/common/subdivision.h"

namespace meshvid {

StatusOr<VideoCodec> CheckStreamHeader(const ContainerHeader& header, const std::string& name) {
  if (header.streams.size() != 1 || header.streams[0].name != "displacement" ||
      header.streams[0].bit_depth != 10) {
    return UnsupportedError(name + ": expected one 10-bit displacement video stream");
  }
  if (header.level_count > static_cast<std::uint32_t>(RegularSubdivision::kMaxLevels)) {
    return CorruptError(name + ": " + std::to_string(header.level_count) + " levels");
  }
  const std::optional<VideoCodec> codec = ParseVideoCodecTag(header.streams[0].codec);
  if (!codec) {
    return UnsupportedError(name + ": video codec '" + header.streams[0].codec +
                            "' is not supported");
  }
  return *codec;
}

}  // namespace meshvid
