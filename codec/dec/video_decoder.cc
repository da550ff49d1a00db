#include "codec/dec/video_decoder.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "codec/dec/ffmpeg_util.h"

namespace meshvid {

struct VideoDecoder::Impl {
  VideoCodec codec;
  int width = 0;
  int height = 0;
  PictureFormat format = PictureFormat::kGrey10;
  AvCodecContextPtr context;
  AvFramePtr frame;
  AvPacketPtr packet;
};

VideoDecoder::~VideoDecoder() = default;

namespace {

const AVCodec* FindDecoder(VideoCodec codec) {
  switch (codec) {
    case VideoCodec::kHevc: return avcodec_find_decoder(AV_CODEC_ID_HEVC);
    case VideoCodec::kAv1: {
      const AVCodec* dav1d = avcodec_find_decoder_by_name("libdav1d");
      return dav1d != nullptr ? dav1d : avcodec_find_decoder(AV_CODEC_ID_AV1);
    }
    case VideoCodec::kFfv1: return avcodec_find_decoder(AV_CODEC_ID_FFV1);
  }
  return nullptr;
}

}  // namespace

StatusOr<std::unique_ptr<VideoDecoder>> VideoDecoder::Create(
    VideoCodec codec, int width, int height, std::span<const std::uint8_t> extradata, int threads,
    PictureFormat format) {
  SilenceFfmpegLogging();
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384) {
    return CorruptError("video size " + std::to_string(width) + "x" + std::to_string(height) +
                        " is out of range");
  }
  const AVCodec* decoder = FindDecoder(codec);
  if (decoder == nullptr) {
    return UnsupportedError("this FFmpeg has no " + std::string(VideoCodecName(codec)) +
                            " decoder");
  }
  std::unique_ptr<VideoDecoder> result(new VideoDecoder());
  result->impl_ = std::make_unique<Impl>();
  Impl& impl = *result->impl_;
  impl.codec = codec;
  impl.width = width;
  impl.height = height;
  impl.format = format;
  impl.context.reset(avcodec_alloc_context3(decoder));
  impl.frame.reset(av_frame_alloc());
  impl.packet.reset(av_packet_alloc());
  if (!impl.context || !impl.frame || !impl.packet) return InternalError("out of memory");
  impl.context->width = width;
  impl.context->height = height;
  impl.context->thread_count = threads;
  if (!extradata.empty()) {
    impl.context->extradata = static_cast<std::uint8_t*>(
        av_mallocz(extradata.size() + AV_INPUT_BUFFER_PADDING_SIZE));
    if (impl.context->extradata == nullptr) return InternalError("out of memory");
    std::memcpy(impl.context->extradata, extradata.data(), extradata.size());
    impl.context->extradata_size = static_cast<int>(extradata.size());
  }
  const int error = avcodec_open2(impl.context.get(), decoder, nullptr);
  // The configuration comes from the file: a decoder that refuses it means damaged data.
  if (error < 0 && (!extradata.empty() || error == AVERROR_INVALIDDATA)) {
    return CorruptError("the " + std::string(VideoCodecName(codec)) + " decoder refuses the " +
                        std::to_string(extradata.size()) + "-byte video configuration: " +
                        FfmpegErrorText(error));
  }
  if (error < 0) return FfmpegError("cannot open the video decoder", error);
  return result;
}

namespace {

/// Copies a decoded frame of the stream's size into `picture`, or says why it cannot.
Status CopyFrame(const AVFrame& frame, int width, int height, GreyPicture* picture) {
  const bool grey10 = frame.format == AV_PIX_FMT_GRAY10LE;
  // AV1 and HEVC decoders may return 4:2:0 when the stream was coded with chroma; the
  // luma plane is what we need either way.
  const bool yuv10 = frame.format == AV_PIX_FMT_YUV420P10LE;
  if ((!grey10 && !yuv10) || frame.width != width || frame.height != height) {
    return CorruptError("decoded picture is not " + std::to_string(width) + "x" +
                        std::to_string(height) + " 10-bit grey");
  }
  picture->samples.resize(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    std::memcpy(picture->samples.data() + static_cast<std::size_t>(y) * width,
                frame.data[0] + static_cast<std::size_t>(y) * frame.linesize[0],
                sizeof(std::uint16_t) * width);
  }
  return Status::Ok();
}

Status CopyFrame(const AVFrame& frame, int width, int height, ColourPicture* picture) {
  // Full-range 4:4:4 may come back under the older full-range name.
  const bool yuv444 = frame.format == AV_PIX_FMT_YUV444P || frame.format == AV_PIX_FMT_YUVJ444P;
  if (!yuv444 || frame.width != width || frame.height != height) {
    return CorruptError("decoded picture is not " + std::to_string(width) + "x" +
                        std::to_string(height) + " 8-bit 4:4:4 colour");
  }
  for (int p = 0; p < 3; ++p) {
    picture->planes[p].resize(static_cast<std::size_t>(width) * height);
    for (int y = 0; y < height; ++y) {
      std::memcpy(picture->planes[p].data() + static_cast<std::size_t>(y) * width,
                  frame.data[p] + static_cast<std::size_t>(y) * frame.linesize[p], width);
    }
  }
  return Status::Ok();
}

constexpr PictureFormat FormatOf(const GreyPicture*) { return PictureFormat::kGrey10; }
constexpr PictureFormat FormatOf(const ColourPicture*) { return PictureFormat::kColour8; }

}  // namespace

Status VideoDecoder::Send(const VideoPacket* packet) {
  Impl& impl = *impl_;
  if (packet == nullptr) {
    const int error = avcodec_send_packet(impl.context.get(), nullptr);
    if (error < 0 && error != AVERROR_EOF) return FfmpegError("cannot flush the decoder", error);
    return Status::Ok();
  }
  if (packet->data.empty()) return CorruptError("empty video packet");
  int error = av_new_packet(impl.packet.get(), static_cast<int>(packet->data.size()));
  if (error < 0) return FfmpegError("cannot allocate a video packet", error);
  std::memcpy(impl.packet->data, packet->data.data(), packet->data.size());
  impl.packet->pts = packet->pts;
  impl.packet->dts = packet->dts;
  if (packet->keyframe) impl.packet->flags |= AV_PKT_FLAG_KEY;
  error = avcodec_send_packet(impl.context.get(), impl.packet.get());
  av_packet_unref(impl.packet.get());
  if (error < 0) return CorruptError("the video stream does not decode: " + FfmpegErrorText(error));
  return Status::Ok();
}

Status VideoDecoder::Decode(const VideoPacket& packet, std::vector<GreyPicture>* out) {
  return SendAndReceive(&packet, out);
}

Status VideoDecoder::Decode(const VideoPacket& packet, std::vector<ColourPicture>* out) {
  return SendAndReceive(&packet, out);
}

Status VideoDecoder::Flush(std::vector<GreyPicture>* out) { return SendAndReceive(nullptr, out); }

Status VideoDecoder::Flush(std::vector<ColourPicture>* out) { return SendAndReceive(nullptr, out); }

template <typename Picture>
Status VideoDecoder::SendAndReceive(const VideoPacket* packet, std::vector<Picture>* out) {
  Impl& impl = *impl_;
  if (FormatOf(static_cast<const Picture*>(nullptr)) != impl.format) {
    return InvalidArgumentError("pictures asked for in another format than the stream's");
  }
  MESHVID_RETURN_IF_ERROR(Send(packet));
  while (true) {
    const int error = avcodec_receive_frame(impl.context.get(), impl.frame.get());
    if (error == AVERROR(EAGAIN) || error == AVERROR_EOF) return Status::Ok();
    if (error < 0) return CorruptError("the video stream does not decode: " + FfmpegErrorText(error));
    const AVFrame& frame = *impl.frame;
    Picture picture;
    picture.width = impl.width;
    picture.height = impl.height;
    picture.pts = frame.best_effort_timestamp != AV_NOPTS_VALUE ? frame.best_effort_timestamp
                                                                : frame.pts;
    const Status copied = CopyFrame(frame, impl.width, impl.height, &picture);
    av_frame_unref(impl.frame.get());
    MESHVID_RETURN_IF_ERROR(copied);
    out->push_back(std::move(picture));
  }
}

}  // namespace meshvid
