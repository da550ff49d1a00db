// Small shared helpers around FFmpeg's C API (error text, quiet logging, RAII deleters).
#ifndef MESHVID_CODEC_DEC_FFMPEG_UTIL_H_
#define MESHVID_CODEC_DEC_FFMPEG_UTIL_H_

#include <memory>
#include <string>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/frame.h>
}

#include "format/status.h"

namespace meshvid {

/// FFmpeg's text for an AVERROR code.
std::string FfmpegErrorText(int error);
/// An internal-error Status "`what`: <FFmpeg's text>".
Status FfmpegError(const std::string& what, int error);
/// Silences FFmpeg's logging (the library never prints); idempotent, thread-safe.
void SilenceFfmpegLogging();

struct AvCodecContextDeleter {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct AvFrameDeleter {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct AvPacketDeleter {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
using AvCodecContextPtr = std::unique_ptr<AVCodecContext, AvCodecContextDeleter>;
using AvFramePtr = std::unique_ptr<AVFrame, AvFrameDeleter>;
using AvPacketPtr = std::unique_ptr<AVPacket, AvPacketDeleter>;

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_FFMPEG_UTIL_H_
