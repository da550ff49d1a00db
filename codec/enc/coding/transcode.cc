#include "codec/enc/coding/transcode.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <vector>

#include "codec/dec/gof_side_info.h"
#include "codec/dec/mvid_decoder.h"
#include "codec/enc/coding/video_encoder.h"
#include "codec/enc/options.h"
#include "format/container_copy.h"
#include "format/container_reader.h"
#include "format/container_writer.h"
#include "format/output_file.h"

namespace meshvid {
namespace {

/// Codes one group's decoded pictures again; replaces its packets and its side information's
/// video configuration record.
Status RecodeGroup(MvidDecoder& source, const VideoEncoding& settings, GroupOfFrames* gof) {
  const std::string context = "group " + std::to_string(gof->gof_index);
  MESHVID_ASSIGN_OR_RETURN(const auto size, source.PictureSizeOf(gof->first_frame));
  VideoEncoding video = settings;
  video.width = size.first;
  video.height = size.second;
  StatusOr<std::unique_ptr<VideoEncoder>> encoder = VideoEncoder::Create(video);
  if (!encoder.ok()) {
    // Such as x265 refusing pictures a few rows high, which FFV1 files of few levels have.
    return UnsupportedError(context + ": " + std::string(VideoCodecName(video.codec)) +
                            " cannot code this key group's " + std::to_string(video.width) + "x" +
                            std::to_string(video.height) + " pictures (" +
                            encoder.status().message() + "); choose another codec");
  }
  std::vector<VideoPacket> packets;
  for (std::uint32_t f = 0; f < gof->frame_count; ++f) {
    MESHVID_ASSIGN_OR_RETURN(const GreyPicture* decoded,
                             source.DisplacementPicture(gof->first_frame + f));
    GreyPicture picture = *decoded;
    picture.pts = f;
    MESHVID_RETURN_IF_ERROR((*encoder)->Encode(picture, f == 0, &packets).WithContext(context));
  }
  MESHVID_RETURN_IF_ERROR((*encoder)->Flush(&packets).WithContext(context));
  StatusOr<std::vector<std::uint8_t>> side =
      ReplaceVideoConfig(gof->transforms, (*encoder)->extradata());
  if (!side.ok()) return side.status().WithContext(context);
  gof->transforms = std::move(*side);
  gof->packets.assign(source.info().colour ? 2 : 1, {});
  for (VideoPacket& packet : packets) gof->packets[0].push_back(std::move(packet.data));
  if (!source.info().colour) return Status::Ok();

  // The colour video, in the same codec, with no configuration record (spec/mvid-codec.md).
  video.format = PictureFormat::kColour8;
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<VideoEncoder> colour_encoder,
                           VideoEncoder::Create(video));
  packets.clear();
  for (std::uint32_t f = 0; f < gof->frame_count; ++f) {
    MESHVID_ASSIGN_OR_RETURN(const ColourPicture* decoded,
                             source.DecodedColourPicture(gof->first_frame + f));
    ColourPicture picture = *decoded;
    picture.pts = f;
    MESHVID_RETURN_IF_ERROR(
        colour_encoder->Encode(picture, f == 0, &packets).WithContext(context + " colour"));
  }
  MESHVID_RETURN_IF_ERROR(colour_encoder->Flush(&packets).WithContext(context + " colour"));
  if (!colour_encoder->extradata().empty()) {
    return InternalError(context + ": the colour video needs a configuration record");
  }
  for (VideoPacket& packet : packets) gof->packets[1].push_back(std::move(packet.data));
  return Status::Ok();
}

/// Decodes every frame's displacements from the input (`before`, already open) and from the
/// written bytes at `written` (the output's temporary file; `output` names it in errors), and
/// measures how far they moved.
Status MeasureChange(MvidDecoder& before, const std::string& written, const std::string& output,
                     const ProgressCallback& progress, TranscodeSummary* summary) {
  StatusOr<std::unique_ptr<MvidDecoder>> after = MvidDecoder::OpenFile(written);
  if (!after.ok()) return after.status().WithContext(output);
  std::vector<float> a, b;
  double sum_squares = 0;
  std::uint64_t samples = 0;
  for (std::uint32_t frame = 0; frame < summary->frames; ++frame) {
    MESHVID_RETURN_IF_ERROR(before.DecodeDisplacements(frame, &a));
    MESHVID_RETURN_IF_ERROR((*after)->DecodeDisplacements(frame, &b).WithContext(output));
    if (a.size() != b.size()) {
      return InternalError(output + ": frame " + std::to_string(frame) + " has " +
                           std::to_string(b.size()) + " displacements, the input " +
                           std::to_string(a.size()));
    }
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double change = std::abs(double(b[i]) - a[i]);
      sum_squares += change * change;
      summary->displacement_max_change = std::max(summary->displacement_max_change, change);
    }
    samples += a.size();
    if (!ReportProgress(progress, "measuring", frame + 1, summary->frames)) {
      return CancelledError("cancelled");
    }
  }
  summary->displacement_rms_change = samples > 0 ? std::sqrt(sum_squares / samples) : 0.0;
  return Status::Ok();
}

}  // namespace

StatusOr<TranscodeSummary> TranscodeVideo(const std::string& input, const std::string& output,
                                          const TranscodeOptions& options) {
  if (options.quality < 0 || options.quality > 100) {
    return InvalidArgumentError("quality must be in 0..100 (got " +
                                std::to_string(options.quality) + ")");
  }
  std::error_code same_error;
  if (std::filesystem::equivalent(input, output, same_error)) {
    return InvalidArgumentError(output + ": is the input; write the transcoded file elsewhere");
  }
  MESHVID_ASSIGN_OR_RETURN(ContainerReader reader, ContainerReader::OpenFile(input));
  MESHVID_RETURN_IF_ERROR(CheckWholeContainer(reader, input));
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<MvidDecoder> source, MvidDecoder::OpenFile(input));

  ContainerHeader header = reader.header();
  // The decoder has checked the streams: the displacements, and perhaps the colour.
  for (StreamInfo& stream : header.streams)
    stream.codec = std::string(VideoCodecTag(options.codec));
  if (!options.metadata_json.empty()) header.metadata_json = options.metadata_json;

  VideoEncoding settings;
  settings.codec = options.codec;
  settings.frame_rate = source->info().frame_rate;
  settings.qp = QualityToQp(options.codec, options.quality);
  settings.effort = options.effort;
  settings.threads = options.threads;

  TranscodeSummary summary;
  summary.frames = source->info().frame_count;
  summary.groups = static_cast<std::uint32_t>(reader.gof_count());
  summary.input_bytes = std::filesystem::file_size(input);
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<OutputFile> file, OutputFile::Open(output));
  ContainerWriter writer(OstreamSink(file->stream(), output));
  MESHVID_RETURN_IF_ERROR(writer.Begin(header));
  const GofRewrite recode = [&](std::size_t g, GroupOfFrames* gof) -> Status {
    for (const auto& stream : gof->packets) {
      for (const auto& packet : stream) summary.input_video_bytes += packet.size();
    }
    MESHVID_RETURN_IF_ERROR(RecodeGroup(*source, settings, gof).WithContext(input));
    for (const auto& stream : gof->packets) {
      for (const auto& packet : stream) summary.output_video_bytes += packet.size();
    }
    if (!ReportProgress(options.progress, "transcoding", long(g) + 1, long(summary.groups))) {
      return CancelledError("cancelled");
    }
    return Status::Ok();
  };
  MESHVID_RETURN_IF_ERROR(CopyGofs(reader, 0, reader.gof_count(), writer, recode));
  MESHVID_RETURN_IF_ERROR(writer.Finish());
  summary.output_bytes = writer.bytes_written();
  // Measured on the written bytes before they become the output: a file that does not decode
  // is never left behind. Bytes written in place to a device cannot be read back.
  if (!file->stream().flush()) return IoError(output + ": write failed");
  if (!file->in_place()) {
    MESHVID_RETURN_IF_ERROR(
        MeasureChange(*source, file->temporary_path(), output, options.progress, &summary));
  }
  MESHVID_RETURN_IF_ERROR(file->Commit());
  return summary;
}

}  // namespace meshvid
