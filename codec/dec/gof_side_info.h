// The codec's side information of a group of frames, carried in the GOF chunk's `transforms`
// field: the displacement quantiser of the group, the configuration record of the group's
// video encoder session (FFV1 needs one; HEVC and AV1 send theirs in-band, so it is empty),
// then the group's transform track payload.
//   u8 side_info_version (2; 1 is read too) | u8 displacement_packing |
//   f32 displacement_minimum | f32 displacement_step |
//   u32 video_config_size | video_config bytes | transforms payload (motion_decoder.h)
#ifndef MESHVID_CODEC_DEC_GOF_SIDE_INFO_H_
#define MESHVID_CODEC_DEC_GOF_SIDE_INFO_H_

#include <cstdint>
#include <span>
#include <vector>

#include "codec/common/displacement_image.h"
#include "codec/common/motion.h"
#include "codec/dec/motion_decoder.h"
#include "format/status.h"

namespace meshvid {

/// Decoded side information of one group.
struct GofSideInfo {
  DisplacementPacking packing = DisplacementPacking::kTriangleBlocks;
  DisplacementRange displacement_range;
  std::vector<std::uint8_t> video_config;  ///< the video decoder's configuration record
  std::vector<std::vector<RigidTransform>> transforms;  ///< [frame in group][segment]
};

/// Parses a group's side information (frame and segment counts as the container says).
StatusOr<GofSideInfo> DecodeGofSideInfo(std::span<const std::uint8_t> bytes,
                                        std::uint32_t frame_count, std::uint32_t segment_count,
                                        const MotionQuantization& quantization);

/// The bytes of a group's side information from its packing, range, video configuration
/// record and coded transforms.
std::vector<std::uint8_t> EncodeGofSideInfo(DisplacementPacking packing,
                                            const DisplacementRange& range,
                                            std::span<const std::uint8_t> video_config,
                                            std::span<const std::uint8_t> transforms_payload);

/// The side information `side_info` with its video configuration record replaced by
/// `video_config`, everything else (version, packing, range, transforms) byte for byte: a group
/// whose video is coded again (`meshvid transcode`). kCorrupt if `side_info` does not parse.
StatusOr<std::vector<std::uint8_t>> ReplaceVideoConfig(std::span<const std::uint8_t> side_info,
                                                       std::span<const std::uint8_t> video_config);

/// The side information `side_info` with its displacement range replaced by `range` and its
/// video configuration record by `video_config`, everything else (version, packing,
/// transforms) byte for byte: a group whose displacements are changed and coded again
/// (`meshvid edit`). kCorrupt if `side_info` does not parse.
StatusOr<std::vector<std::uint8_t>> ReplaceRangeAndVideoConfig(
    std::span<const std::uint8_t> side_info, const DisplacementRange& range,
    std::span<const std::uint8_t> video_config);

/// What a group's video decoder needs of its side information: the displacement packing (which
/// with the key group gives the picture size) and the configuration record.
struct GofVideoHead {
  DisplacementPacking packing = DisplacementPacking::kTriangleBlocks;
  DisplacementRange displacement_range;  ///< finite, with a positive step
  std::vector<std::uint8_t> video_config;
};

/// The packing and video configuration record of side information `side_info`, read without
/// its transforms (which need the key group's motion): a group's video can be decoded before
/// its key group is. kCorrupt / kUnsupported if the fields before them do not parse.
StatusOr<GofVideoHead> ReadGofVideoHead(std::span<const std::uint8_t> side_info);

}  // namespace meshvid

#endif  // MESHVID_CODEC_DEC_GOF_SIDE_INFO_H_
