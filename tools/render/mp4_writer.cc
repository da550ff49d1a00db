#include "tools/render/mp4_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
}

#include "codec/dec/ffmpeg_util.h"
#include "format/output_file.h"

namespace meshvid {

struct Mp4Writer::State {
  std::string path, temporary;
  AVFormatContext* format = nullptr;
  AvCodecContextPtr codec;
  AVStream* stream = nullptr;
  AvFramePtr frame;
  AvPacketPtr packet;
  std::int64_t next_pts = 0;
  bool header_written = false;
  bool finished = false;
  ~State() {
    if (format != nullptr) {
      if (format->pb != nullptr) avio_closep(&format->pb);
      avformat_free_context(format);
    }
    if (!finished && !temporary.empty()) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
    }
  }
};

Mp4Writer::~Mp4Writer() = default;

RgbImage PadToEven(const RgbImage& image) {
  const int width = image.width + (image.width & 1), height = image.height + (image.height & 1);
  if (width == image.width && height == image.height) return image;
  RgbImage out(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* p = image.at(std::min(x, image.width - 1), std::min(y, image.height - 1));
      out.Set(x, y, {p[0], p[1], p[2]});
    }
  }
  return out;
}

StatusOr<std::unique_ptr<Mp4Writer>> Mp4Writer::Create(const std::string& path, int width,
                                                       int height, double frame_rate, int crf) {
  if (width < 2 || height < 2 || (width & 1) || (height & 1)) {
    return InvalidArgumentError("MP4 pictures need an even size, not " + std::to_string(width) +
                                "x" + std::to_string(height));
  }
  if (!(frame_rate > 0)) frame_rate = 25;
  SilenceFfmpegLogging();
  std::unique_ptr<Mp4Writer> writer(new Mp4Writer);
  writer->state_ = std::make_unique<State>();
  State& s = *writer->state_;
  s.path = path;
  s.temporary = path + ".partial";
  MESHVID_RETURN_IF_ERROR(CreateParentFolders(path));
  const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
  if (codec == nullptr) codec = avcodec_find_encoder_by_name("libx265");
  if (codec == nullptr) {
    return InternalError("this FFmpeg has neither libx264 nor libx265 to write MP4 video");
  }
  writer->codec_name_ = codec->name;
  int error = avformat_alloc_output_context2(&s.format, nullptr, "mp4", s.temporary.c_str());
  if (error < 0 || s.format == nullptr) return FfmpegError("cannot start an MP4 file", error);
  s.codec.reset(avcodec_alloc_context3(codec));
  if (!s.codec) return InternalError("cannot allocate a video encoder");
  AVCodecContext* c = s.codec.get();
  c->width = width;
  c->height = height;
  c->pix_fmt = AV_PIX_FMT_YUV420P;
  // The time base in 1/1000 frames keeps rates such as 29.97 exact enough.
  const AVRational rate = av_d2q(frame_rate, 100000);
  c->time_base = av_inv_q(rate);
  c->framerate = rate;
  c->gop_size = 50;
  c->color_range = AVCOL_RANGE_MPEG;
  c->colorspace = AVCOL_SPC_BT470BG;
  if (s.format->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  av_opt_set(c->priv_data, "preset", "medium", 0);
  av_opt_set_int(c->priv_data, "crf", crf, 0);
  if (writer->codec_name_ == "libx265") {
    c->codec_tag = MKTAG('h', 'v', 'c', '1');  // what Apple's players and browsers expect
    av_opt_set(c->priv_data, "x265-params", "log-level=none", 0);
  }
  error = avcodec_open2(c, codec, nullptr);
  if (error < 0) return FfmpegError("cannot open the " + writer->codec_name_ + " encoder", error);
  s.stream = avformat_new_stream(s.format, nullptr);
  if (s.stream == nullptr) return InternalError("cannot add a video stream to the MP4 file");
  s.stream->time_base = c->time_base;
  s.stream->avg_frame_rate = rate;
  error = avcodec_parameters_from_context(s.stream->codecpar, c);
  if (error < 0) return FfmpegError("cannot describe the MP4 video stream", error);
  error = avio_open(&s.format->pb, s.temporary.c_str(), AVIO_FLAG_WRITE);
  if (error < 0) return FfmpegError("cannot open " + s.temporary + " for writing", error);
  error = avformat_write_header(s.format, nullptr);
  if (error < 0) return FfmpegError("cannot write the MP4 header", error);
  s.header_written = true;
  s.frame.reset(av_frame_alloc());
  s.packet.reset(av_packet_alloc());
  if (!s.frame || !s.packet) return InternalError("cannot allocate video frames");
  s.frame->format = AV_PIX_FMT_YUV420P;
  s.frame->width = width;
  s.frame->height = height;
  error = av_frame_get_buffer(s.frame.get(), 0);
  if (error < 0) return FfmpegError("cannot allocate a video picture", error);
  return writer;
}

Status Mp4Writer::AddFrame(const RgbImage& image) {
  State& s = *state_;
  if (s.finished) return InvalidArgumentError("the MP4 file is already finished");
  if (image.width != s.codec->width || image.height != s.codec->height) {
    return InvalidArgumentError("picture of " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " in a video of " +
                                std::to_string(s.codec->width) + "x" +
                                std::to_string(s.codec->height));
  }
  int error = av_frame_make_writable(s.frame.get());
  if (error < 0) return FfmpegError("cannot write a video picture", error);
  AVFrame* f = s.frame.get();
  // RGB to limited-range BT.601 YCbCr; chroma averaged over 2x2 pixels.
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      const float luma = 16.0f + 0.2568f * p[0] + 0.5041f * p[1] + 0.0979f * p[2];
      f->data[0][y * f->linesize[0] + x] = static_cast<std::uint8_t>(luma + 0.5f);
    }
  }
  for (int y = 0; y < image.height / 2; ++y) {
    for (int x = 0; x < image.width / 2; ++x) {
      float r = 0, g = 0, b = 0;
      for (int k = 0; k < 4; ++k) {
        const std::uint8_t* p = image.at(2 * x + (k & 1), 2 * y + (k >> 1));
        r += p[0], g += p[1], b += p[2];
      }
      r /= 4, g /= 4, b /= 4;
      const float cb = 128.0f - 0.1482f * r - 0.2910f * g + 0.4392f * b;
      const float cr = 128.0f + 0.4392f * r - 0.3678f * g - 0.0714f * b;
      f->data[1][y * f->linesize[1] + x] = static_cast<std::uint8_t>(std::clamp(cb + 0.5f, 0.0f, 255.0f));
      f->data[2][y * f->linesize[2] + x] = static_cast<std::uint8_t>(std::clamp(cr + 0.5f, 0.0f, 255.0f));
    }
  }
  f->pts = s.next_pts++;
  error = avcodec_send_frame(s.codec.get(), f);
  if (error < 0) return FfmpegError("video encoding failed", error);
  return Drain();
}

Status Mp4Writer::Drain() {
  State& s = *state_;
  while (true) {
    const int error = avcodec_receive_packet(s.codec.get(), s.packet.get());
    if (error == AVERROR(EAGAIN) || error == AVERROR_EOF) return Status::Ok();
    if (error < 0) return FfmpegError("video encoding failed", error);
    av_packet_rescale_ts(s.packet.get(), s.codec->time_base, s.stream->time_base);
    s.packet->stream_index = s.stream->index;
    const int written = av_interleaved_write_frame(s.format, s.packet.get());
    if (written < 0) return FfmpegError("cannot write to " + s.temporary, written);
  }
}

Status Mp4Writer::Finish() {
  State& s = *state_;
  if (s.finished) return Status::Ok();
  int error = avcodec_send_frame(s.codec.get(), nullptr);
  if (error < 0) return FfmpegError("video encoding failed", error);
  MESHVID_RETURN_IF_ERROR(Drain());
  error = av_write_trailer(s.format);
  if (error < 0) return FfmpegError("cannot finish " + s.temporary, error);
  avio_closep(&s.format->pb);
  std::error_code failed;
  std::filesystem::rename(s.temporary, s.path, failed);
  if (failed) return IoError("cannot rename " + s.temporary + " to " + s.path + ": " + failed.message());
  s.finished = true;
  return Status::Ok();
}

}  // namespace meshvid
