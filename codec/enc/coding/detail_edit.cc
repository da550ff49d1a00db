#include "codec/enc/coding/detail_edit.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "codec/common/displacement_image.h"
#include "codec/common/motion.h"
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

/// Spreads the change of the samples of `level` (a prefix of `change`) to every finer sample:
/// a lattice point takes the change interpolated linearly over the level's triangle it lies in.
void InterpolateFinerSamples(const RegularSubdivision& lattice, int level,
                             std::vector<float>* change) {
  const int n = lattice.segments_per_edge();
  const int h = n >> level;  // the level's spacing in finest lattice steps
  const std::size_t coarse = lattice.sample_count(level);
  for (std::size_t t = 0; t < lattice.base_triangles().size(); ++t) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i + j <= n; ++i) {
        const std::uint32_t s = lattice.LatticeSample(t, i, j);
        if (s < coarse) continue;
        const int i0 = i / h * h, j0 = j / h * h;
        const float u = float(i - i0) / h, v = float(j - j0) / h;
        const auto at = [&](int a, int b) { return (*change)[lattice.LatticeSample(t, a, b)]; };
        (*change)[s] = u + v <= 1.0f
                           ? (1 - u - v) * at(i0, j0) + u * at(i0 + h, j0) + v * at(i0, j0 + h)
                           : (u + v - 1) * at(i0 + h, j0 + h) + (1 - u) * at(i0, j0 + h) +
                                 (1 - v) * at(i0 + h, j0);
      }
    }
  }
}

/// The lowest and highest of `values`.
void Extend(const std::vector<float>& values, float* lowest, float* highest) {
  for (const float d : values) {
    *lowest = std::min(*lowest, d);
    *highest = std::max(*highest, d);
  }
}

}  // namespace

StatusOr<DetailChange> DetailChangeFromPositions(const RegularSubdivision& lattice, int level,
                                                 std::span<const Eigen::Vector3f> decoded,
                                                 std::span<const Eigen::Vector3f> directions,
                                                 std::span<const Eigen::Vector3f> edited) {
  if (level < 0 || level > lattice.levels()) {
    return InvalidArgumentError("level " + std::to_string(level) + " is not in 0.." +
                                std::to_string(lattice.levels()));
  }
  const std::size_t count = lattice.sample_count(level);
  if (decoded.size() != count || directions.size() != count) {
    return InternalError("the decoded frame's vertices are not the level's samples");
  }
  if (edited.size() != count) {
    return InvalidArgumentError("the edited mesh has " + std::to_string(edited.size()) +
                                " vertices; the frame has " + std::to_string(count) + " at level " +
                                std::to_string(level));
  }
  DetailChange result;
  result.change.assign(lattice.samples().size(), 0.0f);
  for (std::size_t s = 0; s < count; ++s) {
    if (!edited[s].allFinite()) {
      return InvalidArgumentError("edited vertex " + std::to_string(s) + " is not finite");
    }
    const Eigen::Vector3f move = edited[s] - decoded[s];
    if (move.isZero(0.0f)) continue;
    ++result.moved_vertices;
    const float along = move.dot(directions[s]);
    result.change[s] = along;
    result.largest_normal_move = std::max(result.largest_normal_move, double(std::abs(along)));
    result.largest_tangential_move =
        std::max(result.largest_tangential_move, double((move - along * directions[s]).norm()));
  }
  InterpolateFinerSamples(lattice, level, &result.change);
  return result;
}

namespace {

/// Adds `change` to the displacements of every frame of group `gof` and codes them again,
/// widening the group's range where the edit needs it; the colour packets stay as they are.
Status EditGroup(MvidDecoder& source, const RegularSubdivision& lattice,
                 const std::vector<float>& change, const VideoEncoding& settings,
                 GroupOfFrames* gof, DetailEditSummary* summary) {
  const std::string context = "group " + std::to_string(gof->gof_index);
  MESHVID_ASSIGN_OR_RETURN(const GofVideoHead head, ReadGofVideoHead(gof->transforms));
  std::vector<std::vector<float>> fields(gof->frame_count);
  const DisplacementRange old_range = head.displacement_range;
  float lowest = old_range.Dequantize(0), highest = old_range.Dequantize(kDisplacementMaxCode);
  const float old_lowest = lowest, old_highest = highest;
  for (std::uint32_t f = 0; f < gof->frame_count; ++f) {
    MESHVID_RETURN_IF_ERROR(source.DecodeDisplacements(gof->first_frame + f, &fields[f]));
    if (fields[f].size() != change.size()) {
      return InternalError(context + ": the frame's samples are not the key group's lattice");
    }
    for (std::size_t s = 0; s < change.size(); ++s) fields[f][s] += change[s];
    Extend(fields[f], &lowest, &highest);
  }
  // An unchanged range keeps every untouched sample's code: only the edit is new.
  DisplacementRange range = old_range;
  if (lowest < old_lowest || highest > old_highest) {
    range = DisplacementRange::Covering(lowest, highest);
    ++summary->ranges_widened;
  }
  const DisplacementLayout layout = DisplacementLayout::ForSubdivision(lattice, head.packing);
  VideoEncoding video = settings;
  video.width = layout.width();
  video.height = layout.height();
  StatusOr<std::unique_ptr<VideoEncoder>> encoder = VideoEncoder::Create(video);
  if (!encoder.ok()) return encoder.status().WithContext(context);
  std::vector<VideoPacket> packets;
  for (std::uint32_t f = 0; f < gof->frame_count; ++f) {
    GreyPicture picture = layout.Pack(fields[f], range);
    picture.pts = f;
    MESHVID_RETURN_IF_ERROR((*encoder)->Encode(picture, f == 0, &packets).WithContext(context));
  }
  MESHVID_RETURN_IF_ERROR((*encoder)->Flush(&packets).WithContext(context));
  StatusOr<std::vector<std::uint8_t>> side =
      ReplaceRangeAndVideoConfig(gof->transforms, range, (*encoder)->extradata());
  if (!side.ok()) return side.status().WithContext(context);
  gof->transforms = std::move(*side);
  gof->packets[0].clear();
  for (VideoPacket& packet : packets) gof->packets[0].push_back(std::move(packet.data));
  ++summary->groups_coded;
  return Status::Ok();
}

}  // namespace

StatusOr<DetailEditSummary> EditDetail(const std::string& input, const std::string& output,
                                       const DetailEditOptions& options) {
  if (options.quality < 0 || options.quality > 100) {
    return InvalidArgumentError("quality must be in 0..100 (got " +
                                std::to_string(options.quality) + ")");
  }
  std::error_code same_error;
  if (std::filesystem::equivalent(input, output, same_error)) {
    return InvalidArgumentError(output + ": is the input; write the edited file elsewhere");
  }
  MESHVID_ASSIGN_OR_RETURN(ContainerReader reader, ContainerReader::OpenFile(input));
  MESHVID_RETURN_IF_ERROR(CheckWholeContainer(reader, input));
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<MvidDecoder> source, MvidDecoder::OpenFile(input));
  const MvidInfo& info = source->info();
  if (options.frame >= info.frame_count) {
    return InvalidArgumentError(input + " has frames 0.." + std::to_string(info.frame_count - 1) +
                                "; frame " + std::to_string(options.frame) + " is not one");
  }
  const int level = options.level < 0 ? info.levels : options.level;
  if (level > info.levels) {
    return InvalidArgumentError(input + " stores levels 0.." + std::to_string(info.levels) +
                                "; level " + std::to_string(level) + " is not one");
  }

  // The edited frame as the decoder reconstructs it: posed base, normals, sample frames.
  std::vector<Eigen::Vector3f> decoded;
  MESHVID_RETURN_IF_ERROR(source->DecodePositions(options.frame, level, &decoded));
  DetailEditSummary summary;
  MESHVID_ASSIGN_OR_RETURN(summary.key_group, source->KeyGroupOf(options.frame));
  const MvidKeyGroupSpan& span = info.key_groups[summary.key_group];
  summary.first_frame = span.first_frame;
  summary.frame_count = span.frame_count;
  MESHVID_ASSIGN_OR_RETURN(const std::vector<RigidTransform> transforms,
                           source->DecodeTransforms(options.frame));
  const TriangleMesh& base = source->base_mesh();
  std::vector<Eigen::Vector3f> posed, normals, origins, directions;
  PoseVertices(source->motion(), transforms, base.positions, &posed);
  ComputeVertexNormals(posed, base.triangles, &normals);
  MESHVID_ASSIGN_OR_RETURN(const RegularSubdivision lattice,
                           RegularSubdivision::Create(base, info.levels));
  EvaluateSampleFrames(lattice, level, posed, normals, &origins, &directions);
  StatusOr<DetailChange> change =
      DetailChangeFromPositions(lattice, level, decoded, directions, options.edited);
  if (!change.ok())
    return change.status().WithContext(input + " frame " + std::to_string(options.frame));

  VideoEncoding settings;
  settings.codec = info.codec;
  settings.frame_rate = info.frame_rate;
  settings.qp = QualityToQp(info.codec, options.quality);
  settings.effort = options.effort;
  settings.threads = options.threads;

  summary.input_bytes = std::filesystem::file_size(input);
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<OutputFile> file, OutputFile::Open(output));
  ContainerWriter writer(OstreamSink(file->stream(), output));
  MESHVID_RETURN_IF_ERROR(writer.Begin(reader.header()));
  const std::size_t first_gof = span.first_gof, end_gof = span.first_gof + span.gof_count;
  const GofRewrite edit = [&](std::size_t g, GroupOfFrames* gof) -> Status {
    if (g < first_gof || g >= end_gof) return Status::Ok();
    MESHVID_RETURN_IF_ERROR(
        EditGroup(*source, lattice, change->change, settings, gof, &summary).WithContext(input));
    if (!ReportProgress(options.progress, "editing", long(g - first_gof) + 1,
                        long(span.gof_count))) {
      return CancelledError("cancelled");
    }
    return Status::Ok();
  };
  MESHVID_RETURN_IF_ERROR(CopyGofs(reader, 0, reader.gof_count(), writer, edit));
  MESHVID_RETURN_IF_ERROR(writer.Finish());
  summary.output_bytes = writer.bytes_written();
  if (!file->stream().flush()) return IoError(output + ": write failed");
  MESHVID_RETURN_IF_ERROR(file->Commit());
  change->change.clear();
  summary.change = std::move(*change);
  return summary;
}

}  // namespace meshvid
