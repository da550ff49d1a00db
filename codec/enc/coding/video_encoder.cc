#include "codec/enc/coding/video_encoder.h"

#include <algorithm>
#include <cstring>
#include <string>

extern "C" {
#include <libavutil/opt.h>
}

#include "codec/dec/ffmpeg_util.h"

namespace meshvid {

struct VideoEncoder::Impl {
  VideoEncoding settings;
  AvCodecContextPtr context;
  AvFramePtr frame;
  AvPacketPtr packet;
};

VideoEncoder::~VideoEncoder() = default;

namespace {

const char* X265Preset(int effort) {
  static const char* const kPresets[] = {"ultrafast", "superfast", "veryfast", "faster",
                                         "fast",      "medium",    "slow",     "slower",
                                         "veryslow",  "placebo"};
  return kPresets[std::clamp(effort, 0, 9)];
}

/// Applies the codec-specific private options.
Status ConfigureCodec(const VideoEncoding& s, AVCodecContext* context) {
  void* priv = context->priv_data;
  switch (s.codec) {
    case VideoCodec::kHevc: {
      // Constant QP; key frames only where the caller starts a group (forced IDR, closed).
      const std::string params = "qp=" + std::to_string(s.qp) +
                                 ":keyint=100000:min-keyint=100000:scenecut=0:open-gop=0"
                                 ":repeat-headers=1:log-level=none";
      if (av_opt_set(priv, "preset", X265Preset(s.effort), 0) < 0 ||
          av_opt_set(priv, "x265-params", params.c_str(), 0) < 0 ||
          av_opt_set_int(priv, "forced-idr", 1, 0) < 0) {
        return InternalError("libx265 rejected its options");
      }
      return Status::Ok();
    }
    case VideoCodec::kAv1: {
      context->gop_size = 100000;
      context->keyint_min = 100000;
      if (av_opt_set_int(priv, "crf", s.qp, 0) < 0 ||
          av_opt_set_int(priv, "cpu-used", std::clamp(8 - s.effort, 0, 8), 0) < 0 ||
          av_opt_set_int(priv, "row-mt", 1, 0) < 0) {
        return InternalError("libaom rejected its options");
      }
      return Status::Ok();
    }
    case VideoCodec::kFfv1: {
      context->gop_size = 1;  // intra only
      if (s.format == PictureFormat::kColour8) {
        // FFV1 version 1 states its parameters in every frame, so the colour stream needs
        // no configuration record (spec/mvid-codec.md, colour video).
        context->level = 1;
        return Status::Ok();
      }
      // FFV1 version 3: its configuration record (extradata) travels with each group.
      context->level = 3;
      context->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
      if (av_opt_set_int(priv, "slicecrc", 1, 0) < 0) {
        return InternalError("ffv1 rejected its options");
      }
      return Status::Ok();
    }
  }
  return InvalidArgumentError("unknown video codec");
}

const AVCodec* FindEncoder(VideoCodec codec) {
  switch (codec) {
    case VideoCodec::kHevc: return avcodec_find_encoder_by_name("libx265");
    case VideoCodec::kAv1: return avcodec_find_encoder_by_name("libaom-av1");
    case VideoCodec::kFfv1: return avcodec_find_encoder(AV_CODEC_ID_FFV1);
  }
  return nullptr;
}

}  // namespace

StatusOr<std::unique_ptr<VideoEncoder>> VideoEncoder::Create(const VideoEncoding& settings) {
  SilenceFfmpegLogging();
  if (settings.width <= 0 || settings.height <= 0 || settings.width % 8 != 0 ||
      settings.height % 8 != 0 || settings.width > 16384 || settings.height > 16384) {
    return InvalidArgumentError("video size must be positive multiples of 8 up to 16384, got " +
                                std::to_string(settings.width) + "x" +
                                std::to_string(settings.height));
  }
  if (!(settings.frame_rate > 0)) return InvalidArgumentError("frame rate must be > 0");
  const int max_qp = settings.codec == VideoCodec::kAv1 ? 63 : 51;
  if (settings.qp < 0 || settings.qp > max_qp) {
    return InvalidArgumentError("video qp must be in 0.." + std::to_string(max_qp) +
                                " for " + std::string(VideoCodecName(settings.codec)));
  }
  const AVCodec* encoder = FindEncoder(settings.codec);
  if (encoder == nullptr) {
    return UnsupportedError("this FFmpeg has no " + std::string(VideoCodecName(settings.codec)) +
                            " encoder");
  }
  std::unique_ptr<VideoEncoder> result(new VideoEncoder());
  result->impl_ = std::make_unique<Impl>();
  Impl& impl = *result->impl_;
  impl.settings = settings;
  impl.context.reset(avcodec_alloc_context3(encoder));
  impl.frame.reset(av_frame_alloc());
  impl.packet.reset(av_packet_alloc());
  if (!impl.context || !impl.frame || !impl.packet) return InternalError("out of memory");
  AVCodecContext* context = impl.context.get();
  context->width = settings.width;
  context->height = settings.height;
  const AVPixelFormat pixel_format =
      settings.format == PictureFormat::kColour8 ? AV_PIX_FMT_YUV444P : AV_PIX_FMT_GRAY10LE;
  context->pix_fmt = pixel_format;
  if (settings.format == PictureFormat::kColour8) {
    // Stated in the stream so that other players read the colour as it was coded
    // (colour_space.h).
    context->color_range = AVCOL_RANGE_JPEG;
    context->colorspace = AVCOL_SPC_BT709;
    context->color_primaries = AVCOL_PRI_BT709;
    context->color_trc = AVCOL_TRC_BT709;
  }
  context->framerate = av_d2q(settings.frame_rate, 100000);
  context->time_base = av_inv_q(context->framerate);
  context->thread_count = settings.threads;
  // HEVC and AV1 send their parameter sets in-band with every key frame, so a group of
  // frames needs no configuration record; FFV1 (below) does.
  MESHVID_RETURN_IF_ERROR(ConfigureCodec(settings, context));
  const int error = avcodec_open2(context, encoder, nullptr);
  if (error < 0) return FfmpegError("cannot open the video encoder", error);
  if (context->extradata_size > 0) {
    result->extradata_.assign(context->extradata, context->extradata + context->extradata_size);
  }
  AVFrame* frame = impl.frame.get();
  frame->format = pixel_format;
  frame->width = settings.width;
  frame->height = settings.height;
  const int alloc_error = av_frame_get_buffer(frame, 0);
  if (alloc_error < 0) return FfmpegError("cannot allocate a video frame", alloc_error);
  return result;
}

Status VideoEncoder::PrepareFrame(int width, int height, std::size_t plane_size,
                                  PictureFormat format) {
  const VideoEncoding& s = impl_->settings;
  if (format != s.format) {
    return InvalidArgumentError(format == PictureFormat::kColour8
                                    ? "a colour picture sent to a grey video encoder"
                                    : "a grey picture sent to a colour video encoder");
  }
  if (width != s.width || height != s.height ||
      plane_size != static_cast<std::size_t>(s.width) * s.height) {
    return InvalidArgumentError("picture is not " + std::to_string(s.width) + "x" +
                                std::to_string(s.height));
  }
  const int error = av_frame_make_writable(impl_->frame.get());
  if (error < 0) return FfmpegError("cannot write a video frame", error);
  return Status::Ok();
}

Status VideoEncoder::SendFrame(std::int64_t pts, bool group_start, std::vector<VideoPacket>* out) {
  AVFrame* frame = impl_->frame.get();
  frame->pts = pts;
  frame->pict_type = group_start ? AV_PICTURE_TYPE_I : AV_PICTURE_TYPE_NONE;
  frame->key_frame = group_start ? 1 : 0;
  const int error = avcodec_send_frame(impl_->context.get(), frame);
  if (error < 0) return FfmpegError("the video encoder rejected a picture", error);
  return Receive(out);
}

Status VideoEncoder::Encode(const GreyPicture& picture, bool group_start,
                            std::vector<VideoPacket>* out) {
  MESHVID_RETURN_IF_ERROR(
      PrepareFrame(picture.width, picture.height, picture.samples.size(), PictureFormat::kGrey10));
  AVFrame* frame = impl_->frame.get();
  for (int y = 0; y < picture.height; ++y) {
    std::memcpy(frame->data[0] + static_cast<std::size_t>(y) * frame->linesize[0],
                picture.samples.data() + static_cast<std::size_t>(y) * picture.width,
                sizeof(std::uint16_t) * picture.width);
  }
  return SendFrame(picture.pts, group_start, out);
}

Status VideoEncoder::Encode(const ColourPicture& picture, bool group_start,
                            std::vector<VideoPacket>* out) {
  for (int p = 1; p < 3; ++p) {
    if (picture.planes[p].size() != picture.planes[0].size()) {
      return InvalidArgumentError("a colour picture's planes differ in size");
    }
  }
  MESHVID_RETURN_IF_ERROR(PrepareFrame(picture.width, picture.height, picture.planes[0].size(),
                                       PictureFormat::kColour8));
  AVFrame* frame = impl_->frame.get();
  for (int p = 0; p < 3; ++p) {
    for (int y = 0; y < picture.height; ++y) {
      std::memcpy(frame->data[p] + static_cast<std::size_t>(y) * frame->linesize[p],
                  picture.planes[p].data() + static_cast<std::size_t>(y) * picture.width,
                  picture.width);
    }
  }
  return SendFrame(picture.pts, group_start, out);
}

Status VideoEncoder::Flush(std::vector<VideoPacket>* out) {
  const int error = avcodec_send_frame(impl_->context.get(), nullptr);
  if (error < 0 && error != AVERROR_EOF) return FfmpegError("cannot flush the encoder", error);
  return Receive(out);
}

Status VideoEncoder::Receive(std::vector<VideoPacket>* out) {
  Impl& impl = *impl_;
  while (true) {
    const int error = avcodec_receive_packet(impl.context.get(), impl.packet.get());
    if (error == AVERROR(EAGAIN) || error == AVERROR_EOF) return Status::Ok();
    if (error < 0) return FfmpegError("the video encoder failed", error);
    const AVPacket& packet = *impl.packet;
    VideoPacket result;
    result.pts = packet.pts;
    result.dts = packet.dts;
    result.keyframe = (packet.flags & AV_PKT_FLAG_KEY) != 0;
    result.data.assign(packet.data, packet.data + packet.size);
    av_packet_unref(impl.packet.get());
    out->push_back(std::move(result));
  }
}

}  // namespace meshvid
