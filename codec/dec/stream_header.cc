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

std::string PartialFileText(std::uint64_t readable, std::uint32_t declared) {
  if (declared <= readable) return "";
  return "partial file: only " + std::to_string(readable) + " of the " + std::to_string(declared) +
         " frames its header promises are readable";
}

Status CheckReadableFrames(std::uint64_t readable, std::uint32_t declared, bool allow_partial,
                           const std::string& name, const std::string& allow_hint) {
  if (readable == 0) {
    const std::string promise =
        declared > 0 ? "the header promises " + std::to_string(declared) + " frames; " : "";
    return CorruptError(name + ": no frame is readable (" + promise +
                        "the file is cut or damaged in its first group of frames)");
  }
  if (declared > readable && !allow_partial) {
    return CorruptError(name + ": " + PartialFileText(readable, declared) +
                        " (the file is cut or damaged; open it with " + allow_hint +
                        " to read those)");
  }
  return Status::Ok();
}

}  // namespace meshvid
