#include "codec/dec/mvid_decoder.h"

#include <algorithm>

#include "codec/dec/base_mesh_decoder.h"
#include "codec/dec/gof_side_info.h"
#include "codec/dec/key_group_geometry.h"
#include "codec/dec/motion_decoder.h"
#include "codec/dec/stream_header.h"
#include "codec/dec/video_decoder.h"
#include "format/stream_reader.h"

namespace meshvid {

/// One decoded group of frames.
struct MvidDecoder::Group {
  std::size_t index = 0;
  std::size_t key_group = 0;
  std::uint32_t first_frame = 0;
  GofSideInfo side;
  const DisplacementLayout* layout = nullptr;  ///< the layout of side.packing
  std::vector<GreyPicture> pictures;  ///< in presentation order, one per frame
  /// The colour stream's packets (files with one), decoded into colour_pictures when colour
  /// is first asked for, so geometry alone never pays for it.
  std::vector<std::vector<std::uint8_t>> colour_packets;
  std::vector<ColourPicture> colour_pictures;  ///< in presentation order, once decoded
  std::uint32_t frame_count = 0;
  std::string context;  ///< "FILE: group K", for errors
};

/// One decoded key group: its geometry and the bytes it came from.
struct MvidDecoder::KeyGroup {
  KeyGroup(std::size_t index, KeyGroupGeometry geometry)
      : index(index), geometry(std::move(geometry)) {}
  std::size_t index = 0;
  KeyGroupGeometry geometry;
  std::uint64_t base_bytes = 0, motion_bytes = 0;
};

/// A key group's payloads as read from the input.
struct KeyGroupBytes {
  std::vector<std::uint8_t> base, motion;
};

MvidDecoder::~MvidDecoder() = default;

/// Where the decoder gets its groups of frames and key groups from.
class MvidDecoder::GroupSource {
 public:
  virtual ~GroupSource() = default;
  /// The group holding `frame` and its key group (kInvalidArgument / kNotFound if no readable
  /// group holds it).
  virtual StatusOr<std::pair<GroupOfFrames, std::size_t>> ReadGroupHolding(
      std::uint32_t frame) = 0;
  /// The BASE and MOTN payloads of key group `k`.
  virtual StatusOr<KeyGroupBytes> ReadKeyGroup(std::size_t k) = 0;
  /// The container reader for random access, or null for a stream.
  virtual ContainerReader* reader() { return nullptr; }
};

/// Groups of a seekable file or memory buffer, found through the index (or a scan).
class MvidDecoder::IndexedGroups : public GroupSource {
 public:
  explicit IndexedGroups(ContainerReader reader) : reader_(std::move(reader)) {}
  StatusOr<std::pair<GroupOfFrames, std::size_t>> ReadGroupHolding(
      std::uint32_t frame) override {
    MESHVID_ASSIGN_OR_RETURN(const std::size_t k, reader_.FindGof(frame));
    MESHVID_ASSIGN_OR_RETURN(GroupOfFrames gof, reader_.ReadGof(k));
    return std::pair{std::move(gof), reader_.KeyGroupOfGof(k)};
  }
  StatusOr<KeyGroupBytes> ReadKeyGroup(std::size_t k) override {
    KeyGroupBytes bytes;
    const bool cut = !reader_.used_index() && !reader_.scan_status().ok();
    auto read = [&](StatusOr<std::vector<std::uint8_t>> payload, const char* type,
                    std::vector<std::uint8_t>* out) -> Status {
      if (!payload.ok()) {
        // A cut file's scan says where it stopped, which explains a missing chunk: the chunk
        // may well be there, cut or damaged, so do not say the file has none.
        return payload.status().code() == StatusCode::kNotFound && cut
                   ? CorruptError(reader_.source().name() + ": key group " + std::to_string(k) +
                                  "'s " + type + " chunk is cut or damaged (the chunk scan " +
                                  "stopped: " + reader_.scan_status().message() + ")")
                   : payload.status();
      }
      *out = std::move(*payload);
      return Status::Ok();
    };
    MESHVID_RETURN_IF_ERROR(read(reader_.ReadBase(k), "BASE", &bytes.base));
    MESHVID_RETURN_IF_ERROR(read(reader_.ReadMotion(k), "MOTN", &bytes.motion));
    return bytes;
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
  StatusOr<std::pair<GroupOfFrames, std::size_t>> ReadGroupHolding(
      std::uint32_t frame) override {
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
      Keep(std::move(item));
    }
    return std::pair{last_, last_key_group_};
  }
  StatusOr<KeyGroupBytes> ReadKeyGroup(std::size_t k) override {
    // Key group 0's chunks come first; later ones arrive before their first group.
    while (k == 0 && pending_key_group_ == 0 &&
           (pending_.base.empty() || pending_.motion.empty()) && next_frame_ == 0) {
      MESHVID_ASSIGN_OR_RETURN(StreamItem item, stream_->Next());
      if (item.kind != StreamItem::Kind::kBase && item.kind != StreamItem::Kind::kMotion) {
        return CorruptError(name_ + ": the base mesh and motion must precede every group");
      }
      Keep(std::move(item));
    }
    if (k != pending_key_group_ || pending_.base.empty() || pending_.motion.empty()) {
      return CorruptError(name_ + ": key group " + std::to_string(k) +
                          " has no BASE and MOTN chunk before its groups of frames");
    }
    return pending_;
  }

 private:
  void Keep(StreamItem item) {
    if (item.kind == StreamItem::Kind::kBase || item.kind == StreamItem::Kind::kMotion) {
      if (item.key_group != pending_key_group_) pending_ = {};
      pending_key_group_ = item.key_group;
      (item.kind == StreamItem::Kind::kBase ? pending_.base : pending_.motion) =
          std::move(item.bytes);
    } else if (item.kind == StreamItem::Kind::kGof) {
      last_ = std::move(item.gof);
      last_key_group_ = item.key_group;
      next_frame_ = last_.first_frame + last_.frame_count;
    }
  }

  std::unique_ptr<StreamReader> stream_;
  std::string name_;
  GroupOfFrames last_;
  std::size_t last_key_group_ = 0;
  KeyGroupBytes pending_;
  std::size_t pending_key_group_ = 0;
  std::uint32_t next_frame_ = 0;
};

std::string PartialFileText(const MvidInfo& info) {
  return PartialFileText(info.frame_count, info.declared_frame_count);
}

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
  MESHVID_RETURN_IF_ERROR(decoder->ReadHeader(reader.header(), reader.source().name()));
  MvidInfo& info = decoder->info_;
  info.frame_count = static_cast<std::uint32_t>(reader.frame_count());
  info.gof_count = static_cast<std::uint32_t>(reader.gof_count());
  info.file_bytes = reader.source().size();
  info.indexed = reader.used_index();
  info.format_version = reader.format_version();
  for (std::size_t k = 0; k < reader.key_groups().size(); ++k) {
    const auto [first, end] = reader.GofsOfKeyGroup(k);
    MvidKeyGroupSpan span;
    span.first_gof = static_cast<std::uint32_t>(first);
    span.gof_count = static_cast<std::uint32_t>(end - first);
    if (end > first) {
      span.first_frame = reader.gofs()[first].first_frame;
      span.frame_count = reader.gofs()[end - 1].first_frame + reader.gofs()[end - 1].frame_count -
                         span.first_frame;
    }
    info.key_groups.push_back(span);
  }
  decoder->groups_ = std::make_unique<IndexedGroups>(std::move(reader));
  MESHVID_RETURN_IF_ERROR(decoder->LoadKeyGroup(0));
  MESHVID_RETURN_IF_ERROR(CheckReadableFrames(info.frame_count, info.declared_frame_count,
                                              options.allow_partial, decoder->name_,
                                              "allow_partial, --allow-partial in meshvid,"));
  return decoder;
}

StatusOr<std::unique_ptr<MvidDecoder>> MvidDecoder::OpenStream(std::istream& in,
                                                               const MvidDecoderOptions& options,
                                                               const std::string& name) {
  std::unique_ptr<MvidDecoder> decoder(new MvidDecoder());
  decoder->options_ = options;
  auto stream = std::make_unique<StreamReader>(in, name);
  MESHVID_ASSIGN_OR_RETURN(const ContainerHeader header, stream->ReadHeader());
  MESHVID_RETURN_IF_ERROR(decoder->ReadHeader(header, name));
  decoder->info_.frame_count = header.frame_count;
  decoder->info_.format_version = stream->format_version();
  decoder->groups_ = std::make_unique<StreamedGroups>(std::move(stream), name);
  MESHVID_RETURN_IF_ERROR(decoder->LoadKeyGroup(0));
  return decoder;
}

Status MvidDecoder::ReadHeader(const ContainerHeader& header, const std::string& name) {
  name_ = name;
  MvidInfo& info = info_;
  MESHVID_ASSIGN_OR_RETURN(info.codec, CheckStreamHeader(header, name));
  info.colour = HasColourStream(header);
  info.frame_rate = double(header.frame_rate_numerator) / header.frame_rate_denominator;
  info.declared_frame_count = header.frame_count;
  info.gof_size = header.gof_size;
  info.levels = static_cast<int>(header.level_count);
  info.picture_width = static_cast<int>(header.streams[0].width);
  info.picture_height = static_cast<int>(header.streams[0].height);
  info.metadata_json = header.metadata_json;
  return Status::Ok();
}

Status MvidDecoder::LoadKeyGroup(std::size_t k) {
  if (key_group_ && key_group_->index == k) return Status::Ok();
  const std::string context = name_ + ": key group " + std::to_string(k);
  MESHVID_ASSIGN_OR_RETURN(const KeyGroupBytes bytes, groups_->ReadKeyGroup(k));
  StatusOr<TriangleMesh> base = DecodeBaseMesh(bytes.base);
  if (!base.ok()) return base.status().WithContext(context + " BASE");
  StatusOr<KeyGroupGeometry> geometry =
      KeyGroupGeometry::Create(std::move(*base), bytes.motion, info_.levels);
  if (!geometry.ok()) return geometry.status().WithContext(context + " MOTN");
  auto key_group = std::make_unique<KeyGroup>(k, std::move(*geometry));
  key_group->base_bytes = bytes.base.size();
  key_group->motion_bytes = bytes.motion.size();
  const KeyGroupGeometry& loaded = key_group->geometry;
  if (k == 0 && info_.vertices_per_level.empty()) {
    MvidInfo& info = info_;
    info.base_vertices = loaded.base().vertex_count();
    info.base_triangles = loaded.base().triangle_count();
    info.segments = loaded.motion().segment_count;
    info.base_bytes = key_group->base_bytes;
    info.motion_bytes = key_group->motion_bytes;
    for (int level = 0; level <= info.levels; ++level) {
      info.vertices_per_level.push_back(loaded.VertexCount(level));
      info.triangles_per_level.push_back(loaded.SurfaceTriangleCount() << (2 * level));
    }
  }
  key_group_ = std::move(key_group);
  return Status::Ok();
}

std::uint32_t MvidDecoder::current_key_group() const {
  return static_cast<std::uint32_t>(key_group_->index);
}

const TriangleMesh& MvidDecoder::base_mesh() const { return key_group_->geometry.base(); }

const MotionModel& MvidDecoder::motion() const { return key_group_->geometry.motion(); }

StatusOr<std::uint32_t> MvidDecoder::KeyGroupOf(std::uint32_t frame) {
  if (ContainerReader* reader = groups_->reader()) {
    MESHVID_ASSIGN_OR_RETURN(const std::size_t gof, reader->FindGof(frame));
    return static_cast<std::uint32_t>(reader->KeyGroupOfGof(gof));
  }
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  return static_cast<std::uint32_t>(group_->key_group);
}

StatusOr<MvidKeyGroupInfo> MvidDecoder::DescribeKeyGroup(std::uint32_t k) {
  if (groups_->reader() == nullptr) {
    return UnsupportedError("describing a key group needs a file or memory buffer");
  }
  if (k >= info_.key_groups.size()) {
    return NotFoundError(name_ + ": key group " + std::to_string(k) + " does not exist (" +
                         std::to_string(info_.key_groups.size()) + " readable)");
  }
  MESHVID_RETURN_IF_ERROR(LoadKeyGroup(k));
  group_.reset();  // the current group must belong to the current key group
  const KeyGroup& key_group = *key_group_;
  const KeyGroupGeometry& geometry = key_group.geometry;
  MvidKeyGroupInfo description;
  description.span = info_.key_groups[k];
  description.base_vertices = geometry.base().vertex_count();
  description.base_triangles = geometry.base().triangle_count();
  description.segments = geometry.motion().segment_count;
  description.base_bytes = key_group.base_bytes;
  description.motion_bytes = key_group.motion_bytes;
  // The picture size follows from the base mesh and the packing; the reference encoder uses
  // lattice order.
  const DisplacementLayout layout = DisplacementLayout::ForSubdivision(
      geometry.subdivision(), DisplacementPacking::kLatticeOrder);
  description.picture_width = layout.width();
  description.picture_height = layout.height();
  for (int level = 0; level <= info_.levels; ++level) {
    description.vertices_per_level.push_back(geometry.VertexCount(level));
    description.triangles_per_level.push_back(geometry.SurfaceTriangleCount() << (2 * level));
  }
  return description;
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
  return &key_group_->geometry.Triangles(level);
}

StatusOr<const std::vector<Triangle>*> MvidDecoder::TrianglesOf(std::uint32_t frame, int level) {
  MESHVID_RETURN_IF_ERROR(CheckLevel(level));
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  return Triangles(level);
}

StatusOr<std::pair<int, int>> MvidDecoder::PictureSizeOf(std::uint32_t frame) {
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  return std::make_pair(group_->layout->width(), group_->layout->height());
}

StatusOr<const GreyPicture*> MvidDecoder::DisplacementPicture(std::uint32_t frame) {
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  return &group_->pictures[frame - group_->first_frame];
}

StatusOr<const ColourPicture*> MvidDecoder::DecodedColourPicture(std::uint32_t frame) {
  if (!info_.colour) return InvalidArgumentError(name_ + " has no colour stream");
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  MESHVID_RETURN_IF_ERROR(DecodeColourVideo(group_.get()));
  return &group_->colour_pictures[frame - group_->first_frame];
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
  MESHVID_ASSIGN_OR_RETURN(const auto read, groups_->ReadGroupHolding(frame));
  const GroupOfFrames& gof = read.first;
  const std::size_t k = gof.gof_index;
  group_.reset();
  MESHVID_RETURN_IF_ERROR(LoadKeyGroup(read.second));
  if (groups_->reader() == nullptr && read.second >= info_.key_groups.size()) {
    info_.key_groups.resize(read.second + 1);  // a stream learns its key groups as it reads
  }
  const std::string context = name_ + ": group " + std::to_string(k);
  auto group = std::make_unique<Group>();
  group->index = k;
  group->key_group = read.second;
  group->first_frame = gof.first_frame;
  // Every error of the payload decoders below names the file and the group.
  StatusOr<GofSideInfo> side = DecodeGofSideInfo(gof.transforms, gof.frame_count,
                                                 key_group_->geometry.motion().segment_count,
                                                 key_group_->geometry.quantization());
  if (!side.ok()) return side.status().WithContext(context);
  group->side = std::move(*side);
  StatusOr<const DisplacementLayout*> layout = key_group_->geometry.CheckedLayout(
      group->side.packing, key_group_->index == 0, info_.picture_width, info_.picture_height);
  if (!layout.ok()) return layout.status().WithContext(context);
  group->layout = *layout;
  StatusOr<std::unique_ptr<VideoDecoder>> created =
      VideoDecoder::Create(info_.codec, group->layout->width(), group->layout->height(),
                           group->side.video_config, options_.threads);
  if (!created.ok()) return created.status().WithContext(context);
  std::unique_ptr<VideoDecoder> video = std::move(*created);
  VideoPacket packet;
  for (std::size_t p = 0; p < gof.packets[0].size(); ++p) {
    packet.data = gof.packets[0][p];
    packet.pts = packet.dts = static_cast<std::int64_t>(p);
    // A group starts with a key frame; FFV1 codes every frame as one.
    packet.keyframe = p == 0 || info_.codec == VideoCodec::kFfv1;
    MESHVID_RETURN_IF_ERROR(video->Decode(packet, &group->pictures).WithContext(context));
    // Stop at the first picture too many rather than keep what a hostile stream makes.
    if (group->pictures.size() > gof.frame_count) break;
  }
  MESHVID_RETURN_IF_ERROR(video->Flush(&group->pictures).WithContext(context));
  if (group->pictures.size() != gof.frame_count) {
    return CorruptError(context + ": the video gives " + std::to_string(group->pictures.size()) +
                        " pictures for " + std::to_string(gof.frame_count) + " frames");
  }
  if (info_.colour) {
    if (gof.packets.size() < 2) return CorruptError(context + ": the colour stream is missing");
    group->colour_packets = gof.packets[1];
  }
  group->frame_count = gof.frame_count;
  group->context = context;
  group_ = std::move(group);
  return Status::Ok();
}

Status MvidDecoder::DecodeColourVideo(Group* group) {
  if (!group->colour_pictures.empty()) return Status::Ok();
  const std::string& context = group->context;
  // The colour video carries no configuration record (spec/mvid-codec.md, colour video).
  StatusOr<std::unique_ptr<VideoDecoder>> created =
      VideoDecoder::Create(info_.codec, group->layout->width(), group->layout->height(), {},
                           options_.threads, PictureFormat::kColour8);
  if (!created.ok()) return created.status().WithContext(context + " colour");
  VideoPacket packet;
  for (std::size_t p = 0; p < group->colour_packets.size(); ++p) {
    packet.data = group->colour_packets[p];
    packet.pts = packet.dts = static_cast<std::int64_t>(p);
    packet.keyframe = p == 0 || info_.codec == VideoCodec::kFfv1;
    MESHVID_RETURN_IF_ERROR(
        (*created)->Decode(packet, &group->colour_pictures).WithContext(context + " colour"));
    if (group->colour_pictures.size() > group->frame_count) break;  // too many: refused below
  }
  MESHVID_RETURN_IF_ERROR(
      (*created)->Flush(&group->colour_pictures).WithContext(context + " colour"));
  if (group->colour_pictures.size() != group->frame_count) {
    const std::size_t pictures = group->colour_pictures.size();
    group->colour_pictures.clear();  // asked again, the same error
    return CorruptError(context + ": the colour video gives " + std::to_string(pictures) +
                        " pictures for " + std::to_string(group->frame_count) + " frames");
  }
  return Status::Ok();
}

StatusOr<MvidStreamSizes> MvidDecoder::MeasureStreams() {
  ContainerReader* reader = groups_->reader();
  if (reader == nullptr) return UnsupportedError("stream sizes need a file or memory buffer");
  MvidStreamSizes sizes;
  sizes.key_group_bytes.assign(reader->key_groups().size(), 0);
  for (std::size_t k = 0; k < reader->key_groups().size(); ++k) {
    MESHVID_ASSIGN_OR_RETURN(const KeyGroupBytes bytes, groups_->ReadKeyGroup(k));
    sizes.base_bytes += bytes.base.size();
    sizes.motion_bytes += bytes.motion.size();
    sizes.key_group_bytes[k] += bytes.base.size() + bytes.motion.size();
  }
  for (std::size_t g = 0; g < reader->gof_count(); ++g) {
    MESHVID_ASSIGN_OR_RETURN(const GroupOfFrames gof, reader->ReadGof(g));
    std::uint64_t bytes = gof.transforms.size();
    sizes.transform_bytes += gof.transforms.size();
    for (const auto& packet : gof.packets[0]) {
      sizes.video_bytes += packet.size();
      bytes += packet.size();
    }
    for (std::size_t stream = 1; stream < gof.packets.size(); ++stream) {
      for (const auto& packet : gof.packets[stream]) {
        sizes.colour_bytes += packet.size();
        bytes += packet.size();
      }
    }
    sizes.key_group_bytes[reader->KeyGroupOfGof(g)] += bytes;
  }
  return sizes;
}

Status MvidDecoder::DecodeDisplacements(std::uint32_t frame, std::vector<float>* displacements) {
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  const std::uint32_t local = frame - group_->first_frame;
  group_->layout->Unpack(group_->pictures[local], group_->side.displacement_range,
                         key_group_->geometry.subdivision().samples().size(), displacements);
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
  key_group_->geometry.Positions(group_->side.transforms[local], group_->pictures[local],
                                 *group_->layout, group_->side.displacement_range, level,
                                 positions);
  return Status::Ok();
}

StatusOr<TriangleMesh> MvidDecoder::DecodeFrame(std::uint32_t frame, int level) {
  TriangleMesh mesh;
  MESHVID_RETURN_IF_ERROR(DecodePositions(frame, level, &mesh.positions));
  MESHVID_ASSIGN_OR_RETURN(const std::vector<Triangle>* triangles, Triangles(level));
  mesh.triangles = *triangles;
  if (info_.colour) MESHVID_RETURN_IF_ERROR(DecodeColours(frame, level, &mesh.colours));
  return mesh;
}

Status MvidDecoder::DecodeColours(std::uint32_t frame, int level, std::vector<Colour>* colours) {
  if (!info_.colour) return InvalidArgumentError(name_ + " has no colour stream");
  MESHVID_RETURN_IF_ERROR(CheckLevel(level));
  MESHVID_RETURN_IF_ERROR(LoadGroupOf(frame));
  MESHVID_RETURN_IF_ERROR(DecodeColourVideo(group_.get()));
  group_->layout->UnpackColour(group_->colour_pictures[frame - group_->first_frame],
                               key_group_->geometry.subdivision().sample_count(level), colours);
  return Status::Ok();
}

}  // namespace meshvid
