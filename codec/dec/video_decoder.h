// Decoding of displacement video packets with libavcodec.
#ifndef MESHVID_CODEC_DEC_VIDEO_DECODER_H_
#define MESHVID_CODEC_DEC_VIDEO_DECODER_H_

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "codec/common/video_codec.h"
#include "format/status.h"

namespace meshvid {

/// Decodes a 10-bit grey (displacement) or 8-bit 4:4:4 (colour) video stream. Feed the packets
/// of one group of frames in decoding order, then Flush(). A decoder serves one group:
/// MvidDecoder creates one per group it decodes.
class VideoDecoder {
 public:
  ~VideoDecoder();
  /// `extradata` is the encoder's global header (may be empty); `threads` 0 lets FFmpeg pick;
  /// `format` is what the stream's pictures must be (a decoded picture of another format is
  /// an error).
  static StatusOr<std::unique_ptr<VideoDecoder>> Create(
      VideoCodec codec, int width, int height, std::span<const std::uint8_t> extradata,
      int threads = 1, PictureFormat format = PictureFormat::kGrey10);
  /// Decodes one packet; appends the pictures it completes (in presentation order) to `out`.
  /// The grey form needs format kGrey10, the colour form kColour8.
  Status Decode(const VideoPacket& packet, std::vector<GreyPicture>* out);
  Status Decode(const VideoPacket& packet, std::vector<ColourPicture>* out);
  /// Drains the pictures still held by the decoder.
  Status Flush(std::vector<GreyPicture>* out);
  Status Flush(std::vector<ColourPicture>* out);

 private:
  VideoDecoder() = default;
  Status Send(const VideoPacket* packet);  ///< null: drain
  /// Checks that `Picture` is the stream's format, sends the packet (null: drain) and appends
  /// the pictures it completes.
  template <typename Picture>
  Status SendAndReceive(const VideoPacket* packet, std::vector<Picture>* out);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_VIDEO_DECODER_H_
