#include "codec/dec/stream_header.h"

#include <optional>

#include "codec/common/subdivision.h"

namespace meshvid {

StatusOr<VideoCodec> CheckStreamHeader(const ContainerHeader& header, const std::string& name) {
  if (header.streams.empty() || header.streams.size() > 2 ||
      header.streams[0].name != "displacement" || header.streams[0].bit_depth != 10) {
    return UnsupportedError(name +
                            ": expected a 10-bit displacement video stream, and at most an "
                            "8-bit colour stream after it");
  }
  if (header.streams.size() == 2) {
    const StreamInfo& displacement = header.streams[0];
    const StreamInfo& colour = header.streams[1];
    if (colour.name != "colour" || colour.bit_depth != 8) {
      return UnsupportedError(name + ": the second stream is not an 8-bit colour stream");
    }
    if (colour.codec != displacement.codec || colour.width != displacement.width ||
        colour.height != displacement.height) {
      return CorruptError(name + ": the colour stream's codec or picture size differs from "
                                 "the displacement stream's");
    }
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

bool HasColourStream(const ContainerHeader& header) { return header.streams.size() == 2; }

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
