// Encoding of displacement pictures as video with libavcodec.
#ifndef MESHVID_CODEC_ENC_CODING_VIDEO_ENCODER_H_
#define MESHVID_CODEC_ENC_CODING_VIDEO_ENCODER_H_

#include <cstdint>
#include <memory>
#include <vector>

#include "codec/common/video_codec.h"
#include "format/status.h"

namespace meshvid {

/// Settings of the displacement video encoder.
struct VideoEncoding {
  VideoCodec codec = VideoCodec::kHevc;
  int width = 0;   ///< multiple of 8
  int height = 0;  ///< multiple of 8
  double frame_rate = 25.0;
  /// Quantiser: HEVC constant QP (0..51), AV1 constant quality (0..63); ignored by FFV1.
  int qp = 16;
  /// Encoder effort: 0 fastest .. 9 slowest (mapped to x265 presets and libaom cpu-used).
  int effort = 4;
  int threads = 0;  ///< 0: let the encoder pick
  /// 10-bit grey (displacements) or 8-bit Y Cb Cr 4:4:4 (colour: HEVC Main 4:4:4, AV1
  /// profile 1, FFV1).
  PictureFormat format = PictureFormat::kGrey10;
};

/// Encodes 10-bit grey or 8-bit 4:4:4 colour pictures (VideoEncoding::format). Every picture passed
/// with `group_start` set begins a new closed group of frames (an IDR / key frame no later frame
/// looks behind), so a decoder can start at any group.
class VideoEncoder {
 public:
  ~VideoEncoder();
  static StatusOr<std::unique_ptr<VideoEncoder>> Create(const VideoEncoding& settings);
  /// The configuration record a decoder needs: FFV1's; empty for HEVC and AV1, which send
  /// their parameter sets in-band with every key frame.
  const std::vector<std::uint8_t>& extradata() const { return extradata_; }
  /// Encodes one picture (width x height samples in 0..1023); appends finished packets.
  /// Fails unless the format is kGrey10.
  Status Encode(const GreyPicture& picture, bool group_start, std::vector<VideoPacket>* out);
  /// Encodes one colour picture; fails unless the format is kColour8.
  Status Encode(const ColourPicture& picture, bool group_start, std::vector<VideoPacket>* out);
  /// Drains the encoder; appends the remaining packets. The encoder cannot be used after.
  Status Flush(std::vector<VideoPacket>* out);

 private:
  VideoEncoder() = default;
  /// Checks the picture's size and format, and makes the frame writable.
  Status PrepareFrame(int width, int height, std::size_t plane_size, PictureFormat format);
  /// Sends the prepared frame and collects the packets it finishes.
  Status SendFrame(std::int64_t pts, bool group_start, std::vector<VideoPacket>* out);
  Status Receive(std::vector<VideoPacket>* out);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<std::uint8_t> extradata_;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_CODING_VIDEO_ENCODER_H_
