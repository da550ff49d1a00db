#include "codec/enc/coding/mvid_writer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "codec/common/deformation_graph.h"
#include "codec/dec/gof_side_info.h"
#include "codec/enc/coding/motion_encoder.h"
#include "codec/enc/coding/video_encoder.h"
#include "format/payloads.h"

namespace meshvid {

MvidWriter::~MvidWriter() = default;

StatusOr<std::unique_ptr<MvidWriter>> MvidWriter::Create(
    ByteSink sink, const TriangleMesh& base, const MotionModel& motion,
    const MvidWriterSettings& settings, const std::vector<std::vector<RigidTransform>>& track) {
  if (settings.gof_size < 1 || settings.gof_size > 1024) {
    return InvalidArgumentError("frames per group must be in 1..1024, got " +
                                std::to_string(settings.gof_size));
  }
  if (!(settings.frame_rate > 0) || settings.frame_rate > 1000) {
    return InvalidArgumentError("frame rate must be in (0, 1000]");
  }
  if (settings.base.allow_reorder) {
    // MOTN's blends and mask and the lattice are indexed by the decoder's base vertices and
    // triangles: a coder that renumbers them without saying how would scramble the motion.
    return InvalidArgumentError(
        "base.allow_reorder must be false: a .mvid indexes its motion and displacements by base "
        "vertex, so the base mesh coder must keep the vertex order or report it");
  }
  std::unique_ptr<MvidWriter> writer(new MvidWriter());
  writer->settings_ = settings;
  writer->container_ = std::make_unique<ContainerWriter>(std::move(sink));
  MESHVID_RETURN_IF_ERROR(writer->StartKeyGroup(base, motion, track));
  return writer;
}

Status MvidWriter::StartKeyGroup(const TriangleMesh& base, const MotionModel& motion,
                                 const std::vector<std::vector<RigidTransform>>& track) {
  MESHVID_RETURN_IF_ERROR(ValidateMotionModel(motion, base.vertex_count()));
  if (!motion.surface_triangles.empty() &&
      motion.surface_triangles.size() != base.triangle_count()) {
    return InvalidArgumentError("the surface mask has " +
                                std::to_string(motion.surface_triangles.size()) +
                                " entries for a base mesh of " +
                                std::to_string(base.triangle_count()) + " triangles");
  }
  if (key_groups_ > 0 && next_gof_ == first_gof_of_key_group_) {
    return InvalidArgumentError("key group " + std::to_string(key_groups_ - 1) +
                                " has no group of frames yet");
  }
  MESHVID_ASSIGN_OR_RETURN(EncodedBaseMesh base_coded, EncodeBaseMesh(base, settings_.base));
  if (base_coded.decoded.vertex_count() != base.vertex_count()) {
    return InternalError("the base mesh coder changed the vertex count");
  }
  // The motion in the decoder's vertex and triangle order.
  MotionModel ordered = motion;
  if (!base_coded.vertex_in_decoded.empty()) {
    for (std::size_t v = 0; v < motion.blends.size(); ++v) {
      ordered.blends[base_coded.vertex_in_decoded[v]] = motion.blends[v];
    }
    for (std::size_t t = 0; t < motion.surface_triangles.size(); ++t) {
      ordered.surface_triangles[base_coded.triangle_in_decoded[t]] = motion.surface_triangles[t];
    }
    for (std::uint32_t& node : ordered.node_vertices) {
      node = base_coded.vertex_in_decoded[node];
    }
  }
  // A deformation graph's blends as a decoder derives them, from the decoded base.
  if (!ordered.node_vertices.empty()) {
    MESHVID_RETURN_IF_ERROR(CompleteNodeBlends(base_coded.decoded, &ordered));
  }
  MESHVID_ASSIGN_OR_RETURN(RegularSubdivision subdivision,
                           RegularSubdivision::Create(base_coded.decoded, settings_.levels));
  // The transforms rounded about the origin at the settings' steps, or about their segments'
  // pivots at the coarser rotation step their reach allows, whichever codes the track in
  // fewer bytes: the pivots save the rotations' bits where the segments are small, but carry
  // the rotations' rounding into the translations, which costs more on smooth rigid motion.
  MotionQuantization quantization = settings_.motion;
  MotionPivots pivots;
  if (!track.empty()) {
    MotionPivots candidate = FindMotionPivots(ordered, base_coded.decoded.positions);
    MotionQuantization coarse = settings_.motion;
    coarse.rotation_step = RotationStepForReach(settings_.motion, candidate.reach);
    const auto group = static_cast<std::size_t>(settings_.gof_size);
    MESHVID_ASSIGN_OR_RETURN(const std::size_t about_origin,
                             EstimateTransformBytes(track, group, quantization));
    MESHVID_ASSIGN_OR_RETURN(const std::size_t about_pivots,
                             EstimateTransformBytes(track, group, coarse, candidate.pivots));
    if (about_pivots < about_origin) {
      quantization = coarse;
      pivots = std::move(candidate);
    }
  }
  MESHVID_ASSIGN_OR_RETURN(const std::vector<std::uint8_t> motion_bytes,
                           EncodeMotionModel(ordered, quantization));
  quantization_ = quantization;
  pivots_ = std::move(pivots);
  decoded_base_ = std::move(base_coded.decoded);
  subdivision_ = std::move(subdivision);
  layout_ = DisplacementLayout::ForSubdivision(subdivision_, settings_.packing);
  motion_ = std::move(ordered);
  if (key_groups_ == 0) MESHVID_RETURN_IF_ERROR(BeginContainer());
  MESHVID_RETURN_IF_ERROR(container_->WriteBase(base_coded.bytes));
  MESHVID_RETURN_IF_ERROR(container_->WriteMotion(motion_bytes));
  stats_.base_bytes += base_coded.bytes.size();
  stats_.motion_bytes += motion_bytes.size();
  stats_.total_bytes = container_->bytes_written();
  first_gof_of_key_group_ = next_gof_;
  ++key_groups_;
  return Status::Ok();
}

Status MvidWriter::BeginContainer() {
  const MvidWriterSettings& settings = settings_;
  ContainerHeader header;
  // Frame rates are stored as a fraction; 1/1001 multiples (29.97) survive exactly.
  header.frame_rate_denominator = 1001;
  header.frame_rate_numerator =
      static_cast<std::uint32_t>(std::lround(settings.frame_rate * 1001));
  header.frame_count = settings.frame_count;
  header.gof_size = static_cast<std::uint32_t>(settings.gof_size);
  header.level_count = static_cast<std::uint32_t>(settings.levels);
  // The picture size of key group 0 (spec/mvid-codec.md: each key group has its own).
  header.streams.push_back({std::string(VideoCodecTag(settings.codec)),
                            static_cast<std::uint32_t>(layout_.width()),
                            static_cast<std::uint32_t>(layout_.height()), 10, "displacement"});
  if (settings.colour) {
    header.streams.push_back({std::string(VideoCodecTag(settings.codec)),
                              static_cast<std::uint32_t>(layout_.width()),
                              static_cast<std::uint32_t>(layout_.height()), 8, "colour"});
  }
  header.metadata_json = settings.metadata_json;
  return container_->Begin(header);
}

std::vector<std::vector<RigidTransform>> MvidWriter::DequantizeTransforms(
    const std::vector<std::vector<RigidTransform>>& transforms) const {
  std::vector<std::vector<RigidTransform>> result;
  for (const auto& frame : transforms) {
    auto& out = result.emplace_back();
    for (std::size_t s = 0; s < frame.size(); ++s) {
      const QuantizedTransform q =
          QuantizeTransform(frame[s], quantization_, PivotOf(pivots_.pivots, s));
      out.push_back(DequantizeTransform(q, quantization_));
    }
  }
  return result;
}

template <typename Picture>
Status MvidWriter::EncodePictures(const std::vector<Picture>& pictures, PictureFormat format,
                                  int qp, std::vector<std::uint8_t>* extradata,
                                  std::vector<std::vector<std::uint8_t>>* packets,
                                  std::uint64_t* bytes) {
  VideoEncoding video;
  video.codec = settings_.codec;
  video.width = layout_.width();
  video.height = layout_.height();
  video.frame_rate = settings_.frame_rate;
  video.qp = qp;
  video.effort = settings_.effort;
  video.threads = settings_.threads;
  video.format = format;
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<VideoEncoder> encoder, VideoEncoder::Create(video));
  std::vector<VideoPacket> coded;
  for (std::size_t f = 0; f < pictures.size(); ++f) {
    MESHVID_RETURN_IF_ERROR(encoder->Encode(pictures[f], f == 0, &coded));
  }
  MESHVID_RETURN_IF_ERROR(encoder->Flush(&coded));
  *extradata = encoder->extradata();
  for (VideoPacket& packet : coded) {
    *bytes += packet.data.size();
    packets->push_back(std::move(packet.data));
  }
  return Status::Ok();
}

Status MvidWriter::WriteGroup(const std::vector<std::vector<RigidTransform>>& transforms,
                              const std::vector<std::vector<float>>& displacements,
                              const std::vector<std::vector<Colour>>& colours) {
  const std::size_t frames = transforms.size();
  if (frames == 0 || frames > static_cast<std::size_t>(settings_.gof_size)) {
    return InvalidArgumentError("a group holds 1.." + std::to_string(settings_.gof_size) +
                                " frames, got " + std::to_string(frames));
  }
  if (displacements.size() != frames) {
    return InvalidArgumentError("a group needs one displacement field per frame");
  }
  if (colours.size() != (settings_.colour ? frames : 0)) {
    return InvalidArgumentError(settings_.colour
                                    ? "a group of a file with colour needs one colour field per frame"
                                    : "colour given for a file without a colour stream");
  }
  const std::size_t samples = subdivision_.samples().size();
  float lowest = std::numeric_limits<float>::infinity();
  float highest = -lowest;
  for (std::size_t f = 0; f < frames; ++f) {
    if (transforms[f].size() != motion_.segment_count) {
      return InvalidArgumentError("frame " + std::to_string(next_frame_ + f) + " has " +
                                  std::to_string(transforms[f].size()) + " transforms for " +
                                  std::to_string(motion_.segment_count) + " segments");
    }
    if (displacements[f].size() != samples) {
      return InvalidArgumentError("frame " + std::to_string(next_frame_ + f) + " has " +
                                  std::to_string(displacements[f].size()) +
                                  " displacements for " + std::to_string(samples) + " samples");
    }
    if (settings_.colour && colours[f].size() != samples) {
      return InvalidArgumentError("frame " + std::to_string(next_frame_ + f) + " has " +
                                  std::to_string(colours[f].size()) + " colours for " +
                                  std::to_string(samples) + " samples");
    }
    for (float d : displacements[f]) {
      if (!std::isfinite(d)) {
        return InvalidArgumentError("frame " + std::to_string(next_frame_ + f) +
                                    " has a NaN or infinite displacement");
      }
      lowest = std::min(lowest, d);
      highest = std::max(highest, d);
    }
  }
  const DisplacementRange range = DisplacementRange::Covering(lowest, highest);
  MESHVID_ASSIGN_OR_RETURN(const EncodedTransforms coded_transforms,
                           EncodeTransforms(transforms, quantization_, pivots_.pivots));

  // One encoder session per group keeps every group self-contained.
  std::vector<GreyPicture> pictures(frames);
  for (std::size_t f = 0; f < frames; ++f) {
    pictures[f] = layout_.Pack(displacements[f], range);
    pictures[f].pts = static_cast<std::int64_t>(f);
  }
  GroupOfFrames gof;
  gof.packets.resize(settings_.colour ? 2 : 1);
  std::vector<std::uint8_t> extradata;
  MESHVID_RETURN_IF_ERROR(EncodePictures(pictures, PictureFormat::kGrey10, settings_.qp,
                                         &extradata, &gof.packets[0], &stats_.video_bytes));
  if (settings_.colour) {
    std::vector<ColourPicture> colour_pictures(frames);
    for (std::size_t f = 0; f < frames; ++f) {
      colour_pictures[f] = layout_.PackColour(colours[f]);
      colour_pictures[f].pts = static_cast<std::int64_t>(f);
    }
    // The colour video carries no configuration record (FFV1 codes it as version 1, which
    // states its parameters in every frame).
    std::vector<std::uint8_t> no_record;
    MESHVID_RETURN_IF_ERROR(EncodePictures(colour_pictures, PictureFormat::kColour8,
                                           settings_.colour_qp, &no_record, &gof.packets[1],
                                           &stats_.colour_bytes));
    if (!no_record.empty()) return InternalError("the colour video needs a configuration record");
  }

  gof.gof_index = next_gof_;
  gof.first_frame = next_frame_;
  gof.frame_count = static_cast<std::uint32_t>(frames);
  gof.transforms =
      EncodeGofSideInfo(settings_.packing, range, extradata, coded_transforms.bytes);
  stats_.transform_bytes += gof.transforms.size();
  MESHVID_RETURN_IF_ERROR(container_->WriteGof(gof));
  next_frame_ += static_cast<std::uint32_t>(frames);
  ++next_gof_;
  stats_.frames = next_frame_;
  stats_.total_bytes = container_->bytes_written();
  return Status::Ok();
}

Status MvidWriter::Finish() {
  MESHVID_RETURN_IF_ERROR(container_->Finish());
  stats_.total_bytes = container_->bytes_written();
  return Status::Ok();
}

}  // namespace meshvid
