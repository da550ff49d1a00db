#include "codec/dec/mvid_decoder.h"

#include <algorithm>

#include "codec/dec/base_mesh_decoder.h"
#include "codec/dec/gof_side_info.h"
#include "codec/dec/motion_decoder.h"
#include "codec/dec/video_decoder.h"

namespace meshvid {

/// One decoded group of frames.
struct MvidDecoder::Group {
  std::size_t index = 0;
  std::uint32_t first_frame = 0;
  GofSideInfo side;
  std::vector<GreyPicture> pictures;  ///< in presentation order, one per frame
};

MvidDecoder::~MvidDecoder() = default;

StatusOr<VideoCodec> VideoCodecFromTag(const std::string& tag) {
  if (tag == "hevc") return VideoCodec::kHevc;
  if (tag == "av01") return VideoCodec::kAv1;
  if (tag == "ffv1") return VideoCodec::kFfv1;
  return UnsupportedError("video codec '" + tag + "' is not supported");
}

StatusOr<std::unique_ptr<MvidDecoder>> MvidDecoder::OpenFile(const std::string& path,
                                                             const MvidDecoderOptions& options) {
  MESHVID_ASSIGN_OR_RETURN(ContainerReader reader, ContainerReader::OpenFile(path));
  return Open(std::move(reader), options);
}

StatusOr<std::unique_ptr<MvidDecoder>> MvidDecoder::OpenMemory(
    std::vector<std::uint8_t> bytes, const MvidDecoderOptions& options) {
  MESHVID_ASSIGN_OR_RETURN(ContainerReader reader, ContainerReader::OpenMemory(std::move(bytes)));
  return Open(std::move(reader), options);
}

StatusOr<std::unique_ptr<MvidDecoder>> MvidDecoder::Open(ContainerReader reader,
                                                         const MvidDecoderOptions& options) {
  std::unique_ptr<MvidDecoder> decoder(new MvidDecoder());
  decoder->options_ = options;
  decoder->reader_ = std::make_unique<ContainerReader>(std::move(reader));
  ContainerReader& r = *decoder->reader_;
  const ContainerHeader& header = r.header();
  const std::string& name = r.source().name();
  if (header.streams.size() != 1 || header.streams[0].name != "displacement" ||
      header.streams[0].bit_depth != 10) {
    return UnsupportedError(name + ": expected one 10-bit displacement video stream");
  }
  if (header.level_count > static_cast<std::uint32_t>(RegularSubdivision::kMaxLevels)) {
    return CorruptError(name + ": " + std::to_string(header.level_count) + " levels");
  }
  MvidInfo& info = decoder->info_;
  MESHVID_ASSIGN_OR_RETURN(info.codec, VideoCodecFromTag(header.streams[0].codec));
  info.frame_rate = double(header.frame_rate_numerator) / header.frame_rate_denominator;
  info.frame_count = static_cast<std::uint32_t>(r.frame_count());
  info.gof_size = header.gof_size;
  info.gof_count = static_cast<std::uint32_t>(r.gof_count());
  info.levels = static_cast<int>(header.level_count);
  info.picture_width = static_cast<int>(header.streams[0].width);
  info.picture_height = static_cast<int>(header.streams[0].height);
  info.metadata_json = header.metadata_json;
  info.file_bytes = r.source().size();
  info.indexed = r.used_index();

  MESHVID_ASSIGN_OR_RETURN(const std::vector<std::uint8_t> base_bytes, r.ReadBase());
  MESHVID_ASSIGN_OR_RETURN(decoder->base_, DecodeBaseMesh(base_bytes));
  MESHVID_ASSIGN_OR_RETURN(const std::vector<std::uint8_t> motion_bytes, r.ReadMotion());
  MESHVID_ASSIGN_OR_RETURN(DecodedMotion motion,
                           DecodeMotionModel(motion_bytes, decoder->base_.vertex_count()));
  decoder->motion_ = std::move(motion.model);
  decoder->quantization_ = motion.quantization;
  MESHVID_ASSIGN_OR_RETURN(decoder->subdivision_,
                           RegularSubdivision::Create(decoder->base_, info.levels));
  decoder->layout_ = DisplacementLayout::ForSubdivision(decoder->subdivision_);
  if (decoder->layout_.width() != info.picture_width ||
      decoder->layout_.height() != info.picture_height) {
    return CorruptError(name + ": displacement picture is " + std::to_string(info.picture_width) +
                        "x" + std::to_string(info.picture_height) + ", the layout of this base " +
                        "mesh and level count needs " + std::to_string(decoder->layout_.width()) +
                        "x" + std::to_string(decoder->layout_.height()));
  }
  info.base_vertices = decoder->base_.vertex_count();
  info.base_triangles = decoder->base_.triangle_count();
  info.segments = decoder->motion_.segment_count;
  info.base_bytes = base_bytes.size();
  info.motion_bytes = motion_bytes.size();
  for (int level = 0; level <= info.levels; ++level) {
    info.vertices_per_level.push_back(decoder->subdivision_.sample_count(level));
    info.triangles_per_level.push_back(decoder->base_.triangle_count() << (2 * level));
  }
  decoder->triangles_.resize(info.levels + 1);
  return decoder;
}

Status MvidDecoder::CheckLevel(int level) const {
  if (level < 0 || level > info_.levels) {
    return InvalidArgumentError("level " + std::to_string(level) + " is not in 0.." +
                                std::to_string(info_.levels));
  }
  return Status::Ok();
}

StatusOr<const std::vector<Triangle>*> MvidDecoder::Triangles(int level) {
  MESHVID_RETURN_IF_ERROR(CheckLevel(level));
  if (triangles_[level].empty()) triangles_[level] = subdivision_.Triangles(level);
  return &triangles_[level];
}

Status MvidDecoder::LoadGroupOf(std::uint32_t frame) {
  if (frame >= info_.frame_count) {
    return InvalidArgumentError("frame " + std::to_string(frame) + " is not in 0.." +
                                std::to_string(info_.frame_count) + " (exclusive)");
  }
  MESHVID_ASSIGN_OR_RETURN(const std::size_t k, reader_->FindGof(frame));
  if (group_ && group_->index == k) return Status::Ok();
  MESHVID_ASSIGN_OR_RETURN(const GroupOfFrames gof, reader_->ReadGof(k));
  const std::string context = reader_->source().name() + ": group " + std::to_string(k);
  auto group = std::make_unique<Group>();
  group->index = k;
  group->first_frame = gof.first_frame;
  MESHVID_ASSIGN_OR_RETURN(group->side, DecodeGofSideInfo(gof.transforms, gof.frame_count,
                                                          motion_.segment_count, quantization_));
  MESHVID_ASSIGN_OR_RETURN(
      std::unique_ptr<VideoDecoder> video,
      VideoDecoder::Create(info_.codec, layout_.width(), layout_.height(),
                           group->side.video_config, options_.threads));
  VideoPacket packet;
  for (std::size_t p = 0; p < gof.packets[0].size(); ++p) {
    packet.data = gof.packets[0][p];
    packet.pts = packet.dts = static_cast<std::int64_t>(p);
    // A group starts with a key frame; FFV1 codes every frame as one.
    packet.keyframe = p == 0 || info_.codec == VideoCodec::kFfv1;
    MESHVID_RETURN_IF_ERROR(video->Decode(packet, &group->pictures).WithContext(context));
  }
  MESHVID_RETURN_IF_ERROR(video->Flush(&group->pictures).WithContext(context));
  if (group->pictures.size() != gof.frame_count) {
    return CorruptError(context + ": the video gives " + std::to_string(group->pictures.size()) +
                        " pictures for " + std::to_string(gof.frame_count) + " frames");
  }
  group_ = std::move(group);
  return Status::Ok();
}

StatusOr<MvidStreamSizes> MvidDecoder::MeasureStreams() {
  MvidStreamSizes sizes;
  for (std::size_t k = 0; k < reader_->gof_count(); ++k) {
    MESHVID_ASSIGN_OR_RETURN(const GroupOfFrames gof, reader_->ReadGof(k));
    sizes.transform_bytes += gof.transforms.size();
    for (const auto& packet : gof.packets[0]) sizes.video_bytes += packet.size();
  }
  return sizes;
}

Status MvidDecoder::DecodeDisplacements(std::uint32_t frame, std::vector<float>* displacements) {
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  const std::uint32_t local = frame - group_->first_frame;
  layout_.Unpack(group_->pictures[local], group_->side.displacement_range,
                 subdivision_.samples().size(), displacements);
  return Status::Ok();
}

StatusOr<std::vector<RigidTransform>> MvidDecoder::DecodeTransforms(std::uint32_t frame) {
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  return group_->side.transforms[frame - group_->first_frame];
}

Status MvidDecoder::DecodePositions(std::uint32_t frame, int level,
                                    std::vector<Eigen::Vector3f>* positions) {
  MESHVID_RETURN_IF_ERROR(CheckLevel(level));
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  const std::uint32_t local = frame - group_->first_frame;
  PoseVertices(motion_, group_->side.transforms[local], base_.positions, &posed_);
  TriangleMesh posed_base;
  posed_base.positions = posed_;
  posed_base.triangles = base_.triangles;
  const std::vector<Eigen::Vector3f> normals = ComputeVertexNormals(posed_base);
  EvaluateSampleFrames(subdivision_, level, posed_, normals, &origins_, &directions_);
  const std::size_t count = subdivision_.sample_count(level);
  layout_.Unpack(group_->pictures[local], group_->side.displacement_range, count,
                 &displacements_);
  positions->resize(count);
  for (std::size_t s = 0; s < count; ++s) {
    (*positions)[s] = origins_[s] + displacements_[s] * directions_[s];
  }
  return Status::Ok();
}

StatusOr<TriangleMesh> MvidDecoder::DecodeFrame(std::uint32_t frame, int level) {
  TriangleMesh mesh;
  MESHVID_RETURN_IF_ERROR(DecodePositions(frame, level, &mesh.positions));
  MESHVID_ASSIGN_OR_RETURN(const std::vector<Triangle>* triangles, Triangles(level));
  mesh.triangles = *triangles;
  return mesh;
}

}  // namespace meshvid
