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
}  // namespace

StatusOr<GofSideInfo> DecodeGofSideInfo(std::span<const std::uint8_t> bytes,
                                        std::uint32_t frame_count, std::uint32_t segment_count,
                                        const MotionQuantization& quantization) {
  ByteReader reader(bytes, "group side information");
  MESHVID_ASSIGN_OR_RETURN(const std::uint8_t version, reader.ReadU8("side_info_version"));
  if (version != 1 && version != kSideInfoVersion) {
    return UnsupportedError("group side information version " + std::to_string(version) +
                            " is not supported (this decoder reads versions 1 and 2)");
  }
  GofSideInfo info;
  MESHVID_ASSIGN_OR_RETURN(const std::uint8_t packing, reader.ReadU8("displacement_packing"));
  if (packing != static_cast<std::uint8_t>(DisplacementPacking::kTriangleBlocks) &&
      packing != static_cast<std::uint8_t>(DisplacementPacking::kLatticeOrder)) {
    return reader.Error("unknown displacement_packing " + std::to_string(packing));
  }
  info.packing = static_cast<DisplacementPacking>(packing);
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t minimum, reader.ReadU32("displacement_minimum"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t step, reader.ReadU32("displacement_step"));
  info.displacement_range.minimum = std::bit_cast<float>(minimum);
  info.displacement_range.step = std::bit_cast<float>(step);
  if (!std::isfinite(info.displacement_range.minimum) ||
      !(info.displacement_range.step > 0 && std::isfinite(info.displacement_range.step))) {
    return reader.Error("displacement range is not finite and increasing");
  }
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t config_size, reader.ReadU32("video_config_size"));
  MESHVID_ASSIGN_OR_RETURN(const std::span<const std::uint8_t> config,
                           reader.ReadBytes(config_size, "video_config"));
  info.video_config.assign(config.begin(), config.end());
  MESHVID_ASSIGN_OR_RETURN(info.transforms,
                           DecodeTransforms(bytes.subspan(reader.position()), frame_count,
                                            segment_count, quantization,
                                            version == 1 ? TransformByteOrder::kInterleaved
                                                         : TransformByteOrder::kBytePlanes));
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
  MESHVID_ASSIGN_OR_RETURN(const std::uint8_t version, reader.ReadU8("side_info_version"));
  if (version != 1 && version != kSideInfoVersion) {
    return UnsupportedError("group side information version " + std::to_string(version) +
                            " is not supported (this decoder reads versions 1 and 2)");
  }
  MESHVID_RETURN_IF_ERROR(reader.ReadU8("displacement_packing").status());
  MESHVID_RETURN_IF_ERROR(reader.ReadU32("displacement_minimum").status());
  MESHVID_RETURN_IF_ERROR(reader.ReadU32("displacement_step").status());
  // Everything before the configuration record's size is kept, and everything after it.
  const std::span<const std::uint8_t> before = side_info.first(reader.position());
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t config_size, reader.ReadU32("video_config_size"));
  MESHVID_RETURN_IF_ERROR(reader.ReadBytes(config_size, "video_config").status());
  ByteWriter writer;
  writer.PutBytes(before);
  writer.PutU32(static_cast<std::uint32_t>(video_config.size()));
  writer.PutBytes(video_config);
  writer.PutBytes(side_info.subspan(reader.position()));
  return writer.Release();
}

}  // namespace meshvid
