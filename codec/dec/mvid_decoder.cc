#include "codec/dec/mvid_decoder.h"

#include <algorithm>

#include "codec/dec/base_mesh_decoder.h"
#include "codec/dec/gof_side_info.h"
#include "codec/dec/motion_decoder.h"
#include "codec/dec/video_decoder.h"
#include "format/stream_reader.h"

namespace meshvid {

/// One decoded group of frames.
struct MvidDecoder::Group {
  std::size_t index = 0;
  std::uint32_t first_frame = 0;
  GofSideInfo side;
  const DisplacementLayout* layout = nullptr;  ///< the layout of side.packing
  std::vector<GreyPicture> pictures;  ///< in presentation order, one per frame
};

MvidDecoder::~MvidDecoder() = default;

/// Where the decoder gets its groups of frames from.
class MvidDecoder::GroupSource {
 public:
  virtual ~GroupSource() = default;
  /// The group holding `frame` (kInvalidArgument if no readable group holds it).
  virtual StatusOr<GroupOfFrames> ReadGroupHolding(std::uint32_t frame) = 0;
  /// The container reader for random access, or null for a stream.
  virtual ContainerReader* reader() { return nullptr; }
};

/// Groups of a seekable file or memory buffer, found through the index (or a scan).
class MvidDecoder::IndexedGroups : public GroupSource {
 public:
  explicit IndexedGroups(ContainerReader reader) : reader_(std::move(reader)) {}
  StatusOr<GroupOfFrames> ReadGroupHolding(std::uint32_t frame) override {
    MESHVID_ASSIGN_OR_RETURN(const std::size_t k, reader_.FindGof(frame));
    return reader_.ReadGof(k);
  }
  ContainerReader* reader() override { return &reader_; }

 private:
  ContainerReader reader_;
};

/// Groups of a stream, read front to back.
class MvidDecoder::StreamedGroups : public GroupSource {
 public:
  StreamedGroups(std::unique_ptr<StreamReader> stream, std::string name)
      : stream_(std::move(stream)), name_(std::move(name)) {}
  StatusOr<GroupOfFrames> ReadGroupHolding(std::uint32_t frame) override {
    if (frame < last_.first_frame) {
      return InvalidArgumentError(name_ + ": a stream decodes forward only; frame " +
                                  std::to_string(frame) + " has passed");
    }
    while (frame >= next_frame_) {
      MESHVID_ASSIGN_OR_RETURN(StreamItem item, stream_->Next());
      if (item.kind == StreamItem::Kind::kEnd || item.kind == StreamItem::Kind::kIndex) {
        return InvalidArgumentError(name_ + ": the stream ends after frame " +
                                    std::to_string(next_frame_) + " (exclusive)");
      }
      if (item.kind != StreamItem::Kind::kGof) continue;
      last_ = std::move(item.gof);
      next_frame_ = last_.first_frame + last_.frame_count;
    }
    return last_;
  }

 private:
  std::unique_ptr<StreamReader> stream_;
  std::string name_;
  GroupOfFrames last_;
  std::uint32_t next_frame_ = 0;
};

StatusOr<std::unique_ptr<MvidDecoder>> MvidDecoder::OpenFile(const std::string& path,
                                                             const MvidDecoderOptions& options) {
  MESHVID_ASSIGN_OR_RETURN(ContainerReader reader, ContainerReader::OpenFile(path));
  return OpenIndexed(std::move(reader), options);
}

StatusOr<std::unique_ptr<MvidDecoder>> MvidDecoder::OpenMemory(
    std::vector<std::uint8_t> bytes, const MvidDecoderOptions& options) {
  MESHVID_ASSIGN_OR_RETURN(ContainerReader reader, ContainerReader::OpenMemory(std::move(bytes)));
  return OpenIndexed(std::move(reader), options);
}

StatusOr<std::unique_ptr<MvidDecoder>> MvidDecoder::OpenIndexed(
    ContainerReader reader, const MvidDecoderOptions& options) {
  std::unique_ptr<MvidDecoder> decoder(new MvidDecoder());
  decoder->options_ = options;
  MESHVID_ASSIGN_OR_RETURN(const std::vector<std::uint8_t> base_bytes, reader.ReadBase());
  MESHVID_ASSIGN_OR_RETURN(const std::vector<std::uint8_t> motion_bytes, reader.ReadMotion());
  MESHVID_RETURN_IF_ERROR(
      decoder->Initialize(reader.header(), base_bytes, motion_bytes, reader.source().name()));
  MvidInfo& info = decoder->info_;
  info.frame_count = static_cast<std::uint32_t>(reader.frame_count());
  info.gof_count = static_cast<std::uint32_t>(reader.gof_count());
  info.file_bytes = reader.source().size();
  info.indexed = reader.used_index();
  decoder->groups_ = std::make_unique<IndexedGroups>(std::move(reader));
  return decoder;
}

StatusOr<std::unique_ptr<MvidDecoder>> MvidDecoder::OpenStream(std::istream& in,
                                                               const MvidDecoderOptions& options,
                                                               const std::string& name) {
  std::unique_ptr<MvidDecoder> decoder(new MvidDecoder());
  decoder->options_ = options;
  auto stream = std::make_unique<StreamReader>(in, name);
  MESHVID_ASSIGN_OR_RETURN(const ContainerHeader header, stream->ReadHeader());
  // BASE and MOTN come before the first group (container chunk order rules).
  std::vector<std::uint8_t> base_bytes, motion_bytes;
  while (base_bytes.empty() || motion_bytes.empty()) {
    MESHVID_ASSIGN_OR_RETURN(StreamItem item, stream->Next());
    if (item.kind == StreamItem::Kind::kBase) {
      base_bytes = std::move(item.bytes);
    } else if (item.kind == StreamItem::Kind::kMotion) {
      motion_bytes = std::move(item.bytes);
    } else {
      return CorruptError(name + ": the base mesh and motion must precede every group");
    }
  }
  MESHVID_RETURN_IF_ERROR(decoder->Initialize(header, base_bytes, motion_bytes, name));
  decoder->info_.frame_count = header.frame_count;
  decoder->groups_ = std::make_unique<StreamedGroups>(std::move(stream), name);
  return decoder;
}

Status MvidDecoder::Initialize(const ContainerHeader& header,
                               const std::vector<std::uint8_t>& base_bytes,
                               const std::vector<std::uint8_t>& motion_bytes,
                               const std::string& name) {
  if (header.streams.size() != 1 || header.streams[0].name != "displacement" ||
      header.streams[0].bit_depth != 10) {
    return UnsupportedError(name + ": expected one 10-bit displacement video stream");
  }
  if (header.level_count > static_cast<std::uint32_t>(RegularSubdivision::kMaxLevels)) {
    return CorruptError(name + ": " + std::to_string(header.level_count) + " levels");
  }
  MvidInfo& info = info_;
  const std::optional<VideoCodec> codec = ParseVideoCodecTag(header.streams[0].codec);
  if (!codec) {
    return UnsupportedError(name + ": video codec '" + header.streams[0].codec +
                            "' is not supported");
  }
  info.codec = *codec;
  info.frame_rate = double(header.frame_rate_numerator) / header.frame_rate_denominator;
  info.gof_size = header.gof_size;
  info.levels = static_cast<int>(header.level_count);
  info.picture_width = static_cast<int>(header.streams[0].width);
  info.picture_height = static_cast<int>(header.streams[0].height);
  info.metadata_json = header.metadata_json;
  MESHVID_ASSIGN_OR_RETURN(base_, DecodeBaseMesh(base_bytes));
  MESHVID_ASSIGN_OR_RETURN(DecodedMotion motion,
                           DecodeMotionModel(motion_bytes, base_.vertex_count(),
                                             base_.triangle_count()));
  motion_ = std::move(motion.model);
  quantization_ = motion.quantization;
  MESHVID_ASSIGN_OR_RETURN(subdivision_, RegularSubdivision::Create(base_, info.levels));
  info.base_vertices = base_.vertex_count();
  info.base_triangles = base_.triangle_count();
  info.segments = motion_.segment_count;
  info.base_bytes = base_bytes.size();
  info.motion_bytes = motion_bytes.size();
  for (int level = 0; level <= info.levels; ++level) {
    info.vertices_per_level.push_back(subdivision_.sample_count(level));
    info.triangles_per_level.push_back(SurfaceTriangleCount() << (2 * level));
  }
  triangles_.resize(info.levels + 1);
  return Status::Ok();
}

StatusOr<const DisplacementLayout*> MvidDecoder::LayoutFor(DisplacementPacking packing) {
  auto it = layouts_.find(packing);
  if (it == layouts_.end()) {
    it = layouts_.emplace(packing, DisplacementLayout::ForSubdivision(subdivision_, packing)).first;
  }
  const DisplacementLayout& layout = it->second;
  if (layout.width() != info_.picture_width || layout.height() != info_.picture_height) {
    return CorruptError("displacement picture is " + std::to_string(info_.picture_width) + "x" +
                        std::to_string(info_.picture_height) + ", the packing of this base " +
                        "mesh and level count needs " + std::to_string(layout.width()) + "x" +
                        std::to_string(layout.height()));
  }
  return &layout;
}

Status MvidDecoder::CheckLevel(int level) const {
  if (level < 0 || level > info_.levels) {
    return InvalidArgumentError("level " + std::to_string(level) + " is not in 0.." +
                                std::to_string(info_.levels));
  }
  return Status::Ok();
}

std::size_t MvidDecoder::SurfaceTriangleCount() const {
  if (motion_.surface_triangles.empty()) return base_.triangle_count();
  std::size_t count = 0;
  for (std::uint8_t kept : motion_.surface_triangles) count += kept != 0;
  return count;
}

StatusOr<const std::vector<Triangle>*> MvidDecoder::Triangles(int level) {
  MESHVID_RETURN_IF_ERROR(CheckLevel(level));
  if (triangles_[level].empty()) {
    triangles_[level] = subdivision_.Triangles(level);
    if (!motion_.surface_triangles.empty()) {
      // Level l has 4^l triangles per base triangle, base triangle by base triangle.
      const std::size_t per_base = std::size_t(1) << (2 * level);
      std::size_t kept = 0;
      for (std::size_t t = 0; t < motion_.surface_triangles.size(); ++t) {
        if (!motion_.surface_triangles[t]) continue;
        for (std::size_t k = 0; k < per_base; ++k) {
          triangles_[level][kept++] = triangles_[level][t * per_base + k];
        }
      }
      triangles_[level].resize(kept);
    }
  }
  return &triangles_[level];
}

Status MvidDecoder::LoadGroupOf(std::uint32_t frame) {
  // A stream whose header did not know the frame count learns it at its end.
  const bool count_known = groups_->reader() != nullptr || info_.frame_count > 0;
  if (count_known && frame >= info_.frame_count) {
    return InvalidArgumentError("frame " + std::to_string(frame) + " is not in 0.." +
                                std::to_string(info_.frame_count) + " (exclusive)");
  }
  if (group_ && frame >= group_->first_frame &&
      frame < group_->first_frame + group_->pictures.size()) {
    return Status::Ok();
  }
  MESHVID_ASSIGN_OR_RETURN(const GroupOfFrames gof, groups_->ReadGroupHolding(frame));
  const std::size_t k = gof.gof_index;
  const std::string context = "group " + std::to_string(k);
  auto group = std::make_unique<Group>();
  group->index = k;
  group->first_frame = gof.first_frame;
  MESHVID_ASSIGN_OR_RETURN(group->side, DecodeGofSideInfo(gof.transforms, gof.frame_count,
                                                          motion_.segment_count, quantization_));
  MESHVID_ASSIGN_OR_RETURN(group->layout, LayoutFor(group->side.packing));
  MESHVID_ASSIGN_OR_RETURN(
      std::unique_ptr<VideoDecoder> video,
      VideoDecoder::Create(info_.codec, info_.picture_width, info_.picture_height,
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
  ContainerReader* reader = groups_->reader();
  if (reader == nullptr) return UnsupportedError("stream sizes need a file or memory buffer");
  MvidStreamSizes sizes;
  for (std::size_t k = 0; k < reader->gof_count(); ++k) {
    MESHVID_ASSIGN_OR_RETURN(const GroupOfFrames gof, reader->ReadGof(k));
    sizes.transform_bytes += gof.transforms.size();
    for (const auto& packet : gof.packets[0]) sizes.video_bytes += packet.size();
  }
  return sizes;
}

Status MvidDecoder::DecodeDisplacements(std::uint32_t frame, std::vector<float>* displacements) {
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  const std::uint32_t local = frame - group_->first_frame;
  group_->layout->Unpack(group_->pictures[local], group_->side.displacement_range,
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
  ComputeVertexNormals(posed_, base_.triangles, &normals_);
  EvaluateSampleFrames(subdivision_, level, posed_, normals_, &origins_, &directions_);
  const std::size_t count = subdivision_.sample_count(level);
  group_->layout->Unpack(group_->pictures[local], group_->side.displacement_range, count,
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
