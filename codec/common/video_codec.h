// The video codecs a displacement stream may use, with their identifiers on disk.
#ifndef MESHVID_CODEC_COMMON_VIDEO_CODEC_H_
#define MESHVID_CODEC_COMMON_VIDEO_CODEC_H_

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace meshvid {

/// A displacement video codec. The values are stored in files: never renumber.
enum class VideoCodec : std::uint8_t {
  kHevc = 1,  ///< HEVC Main10 4:0:0 (libx265 to encode, FFmpeg's hevc decoder)
  kAv1 = 2,   ///< AV1 monochrome 10-bit (libaom to encode, dav1d to decode)
  kFfv1 = 3,  ///< FFV1, lossless
};

/// "hevc", "av1", "ffv1".
std::string_view VideoCodecName(VideoCodec codec);
/// Parses a name as printed by VideoCodecName.
std::optional<VideoCodec> ParseVideoCodec(std::string_view name);

/// The codec's tag in the container's stream table: "hevc", "av01", "ffv1".
std::string_view VideoCodecTag(VideoCodec codec);
/// Parses a stream-table tag as written by VideoCodecTag.
std::optional<VideoCodec> ParseVideoCodecTag(std::string_view tag);

/// One coded access unit of a displacement video.
struct VideoPacket {
  std::int64_t pts = 0;  ///< presentation index of the frame it completes
  std::int64_t dts = 0;  ///< decoding order
  bool keyframe = false;
  std::vector<std::uint8_t> data;
};

/// What a video stream's pictures hold. The values are not stored in files.
enum class PictureFormat : std::uint8_t {
  kGrey10,   ///< one 10-bit plane (displacements): GreyPicture
  kColour8,  ///< three full-resolution 8-bit planes, Y Cb Cr 4:4:4 (colour): ColourPicture
};

/// One grey picture: width x height samples of `bit_depth` bits, row-major, no padding.
struct GreyPicture {
  int width = 0;
  int height = 0;
  std::int64_t pts = 0;
  std::vector<std::uint16_t> samples;
};

/// One colour picture: Y, Cb and Cr planes of width x height 8-bit samples each (4:4:4),
/// row-major, no padding.
struct ColourPicture {
  int width = 0;
  int height = 0;
  std::int64_t pts = 0;
  std::array<std::vector<std::uint8_t>, 3> planes;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_VIDEO_CODEC_H_
