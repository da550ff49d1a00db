#include "codec/dec/gof_side_info.h"

#include <bit>
#include <cmath>
#include <string>

#include "format/byte_io.h"

namespace meshvid {
namespace {
/// The version encoders write: 2, the transforms' deltas in byte planes. Version 1 (each
/// delta's bytes together) is still read.
constexpr std::uint8_t kSideInfoVersion = 2;

/// A side information's fields up to and with its video configuration record, which need no
/// key group to parse (the transforms after them need its motion), and where they lie.
struct SideInfoHead {
  std::uint8_t version = 0;
  std::uint8_t packing = 0;
  std::uint32_t minimum = 0, step = 0;  ///< the displacement range's floats' bits
  std::size_t config_size_at = 0;       ///< offset of video_config_size
  std::span<const std::uint8_t> config;
  std::size_t transforms_at = 0;  ///< offset of the transforms payload
};

StatusOr<SideInfoHead> ReadHead(ByteReader& reader) {
  SideInfoHead head;
  MESHVID_ASSIGN_OR_RETURN(head.version, reader.ReadU8("side_info_version"));
  if (head.version != 1 && head.version != kSideInfoVersion) {
    return UnsupportedError("group side information version " + std::to_string(head.version) +
                            " is not supported (this decoder reads versions 1 and 2)");
  }
  MESHVID_ASSIGN_OR_RETURN(head.packing, reader.ReadU8("displacement_packing"));
  MESHVID_ASSIGN_OR_RETURN(head.minimum, reader.ReadU32("displacement_minimum"));
  MESHVID_ASSIGN_OR_RETURN(head.step, reader.ReadU32("displacement_step"));
  head.config_size_at = reader.position();
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t config_size, reader.ReadU32("video_config_size"));
  MESHVID_ASSIGN_OR_RETURN(head.config, reader.ReadBytes(config_size, "video_config"));
  head.transforms_at = reader.position();
  return head;
}

/// `head`'s packing, kCorrupt (through `reader`) if it is none meshvid knows.
StatusOr<DisplacementPacking> PackingOf(const SideInfoHead& head, const ByteReader& reader) {
  if (head.packing != static_cast<std::uint8_t>(DisplacementPacking::kTriangleBlocks) &&
      head.packing != static_cast<std::uint8_t>(DisplacementPacking::kLatticeOrder)) {
    return reader.Error("unknown displacement_packing " + std::to_string(head.packing));
  }
  return static_cast<DisplacementPacking>(head.packing);
}

/// `head`'s displacement range, kCorrupt (through `reader`) unless it is finite and increasing.
StatusOr<DisplacementRange> RangeOf(const SideInfoHead& head, const ByteReader& reader) {
  DisplacementRange range;
  range.minimum = std::bit_cast<float>(head.minimum);
  range.step = std::bit_cast<float>(head.step);
  if (!std::isfinite(range.minimum) || !(range.step > 0 && std::isfinite(range.step))) {
    return reader.Error("displacement range is not finite and increasing");
  }
  return range;
}

}  // namespace

StatusOr<GofSideInfo> DecodeGofSideInfo(std::span<const std::uint8_t> bytes,
                                        std::uint32_t frame_count, std::uint32_t segment_count,
                                        const MotionQuantization& quantization) {
  ByteReader reader(bytes, "group side information");
  MESHVID_ASSIGN_OR_RETURN(const SideInfoHead head, ReadHead(reader));
  GofSideInfo info;
  MESHVID_ASSIGN_OR_RETURN(info.packing, PackingOf(head, reader));
  MESHVID_ASSIGN_OR_RETURN(info.displacement_range, RangeOf(head, reader));
  info.video_config.assign(head.config.begin(), head.config.end());
  MESHVID_ASSIGN_OR_RETURN(
      info.transforms,
      DecodeTransforms(
          bytes.subspan(head.transforms_at), frame_count, segment_count, quantization,
          head.version == 1 ? TransformByteOrder::kInterleaved : TransformByteOrder::kBytePlanes));
  return info;
}

std::vector<std::uint8_t> EncodeGofSideInfo(DisplacementPacking packing,
                                            const DisplacementRange& range,
                                            std::span<const std::uint8_t> video_config,
                                            std::span<const std::uint8_t> transforms_payload) {
  ByteWriter writer;
  writer.PutU8(kSideInfoVersion);
  writer.PutU8(static_cast<std::uint8_t>(packing));
  writer.PutU32(std::bit_cast<std::uint32_t>(range.minimum));
  writer.PutU32(std::bit_cast<std::uint32_t>(range.step));
  writer.PutU32(static_cast<std::uint32_t>(video_config.size()));
  writer.PutBytes(video_config);
  writer.PutBytes(transforms_payload);
  return writer.Release();
}

StatusOr<std::vector<std::uint8_t>> ReplaceVideoConfig(std::span<const std::uint8_t> side_info,
                                                       std::span<const std::uint8_t> video_config) {
  ByteReader reader(side_info, "group side information");
  MESHVID_ASSIGN_OR_RETURN(const SideInfoHead head, ReadHead(reader));
  // Everything before the configuration record's size is kept, and everything after it.
  ByteWriter writer;
  writer.PutBytes(side_info.first(head.config_size_at));
  writer.PutU32(static_cast<std::uint32_t>(video_config.size()));
  writer.PutBytes(video_config);
  writer.PutBytes(side_info.subspan(head.transforms_at));
  return writer.Release();
}

StatusOr<std::vector<std::uint8_t>> ReplaceRangeAndVideoConfig(
    std::span<const std::uint8_t> side_info, const DisplacementRange& range,
    std::span<const std::uint8_t> video_config) {
  ByteReader reader(side_info, "group side information");
  MESHVID_ASSIGN_OR_RETURN(const SideInfoHead head, ReadHead(reader));
  ByteWriter writer;
  writer.PutU8(head.version);
  writer.PutU8(head.packing);
  writer.PutU32(std::bit_cast<std::uint32_t>(range.minimum));
  writer.PutU32(std::bit_cast<std::uint32_t>(range.step));
  writer.PutU32(static_cast<std::uint32_t>(video_config.size()));
  writer.PutBytes(video_config);
  writer.PutBytes(side_info.subspan(head.transforms_at));
  return writer.Release();
}

StatusOr<GofVideoHead> ReadGofVideoHead(std::span<const std::uint8_t> side_info) {
  ByteReader reader(side_info, "group side information");
  MESHVID_ASSIGN_OR_RETURN(const SideInfoHead head, ReadHead(reader));
  GofVideoHead video;
  MESHVID_ASSIGN_OR_RETURN(video.packing, PackingOf(head, reader));
  MESHVID_ASSIGN_OR_RETURN(video.displacement_range, RangeOf(head, reader));
  video.video_config.assign(head.config.begin(), head.config.end());
  return video;
}

}  // namespace meshvid
