// The typed payloads of the .mvid chunks that this layer understands (HEAD, GOF, INDX, TRLR)
// and their byte encodings. BASE, MOTN, per-GOF transforms and video packets stay opaque bytes
// filled by the codec. Field names match spec/mvid-container.md.
#ifndef MESHVID_FORMAT_PAYLOADS_H_
#define MESHVID_FORMAT_PAYLOADS_H_

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// Sanity bounds applied while decoding, before anything is allocated.
inline constexpr uint32_t kMaxStreams = 64;            ///< streams in the stream table
inline constexpr uint32_t kMaxStreamNameSize = 255;    ///< bytes of StreamInfo::name
inline constexpr uint32_t kMaxCodecTagSize = 4;        ///< StreamInfo::codec is a fourcc

/// One entry of the stream table: a displacement (or other) video stream.
struct StreamInfo {
  std::string codec;       ///< four-character codec tag, e.g. "hevc", "av01", "ffv1"
  uint32_t width = 0;      ///< picture width in samples
  uint32_t height = 0;     ///< picture height in samples
  uint32_t bit_depth = 0;  ///< bits per sample
  std::string name;        ///< what the stream carries, e.g. "displacement"
  bool operator==(const StreamInfo&) const = default;
};

/// The HEAD chunk.
struct ContainerHeader {
  uint32_t frame_rate_numerator = 30;   ///< frames per second = numerator / denominator
  uint32_t frame_rate_denominator = 1;  ///< must be > 0
  uint32_t frame_count = 0;             ///< total frames, 0 if unknown when HEAD was written
  uint32_t gof_size = 0;                ///< nominal frames per group of frames (last may be shorter)
  uint32_t level_count = 0;             ///< subdivision levels stored in the displacements
  std::vector<StreamInfo> streams;      ///< stream table; every GOF has one packet list per entry
  std::string metadata_json;            ///< UTF-8 JSON object, opaque to this layer ("" = none)
  bool operator==(const ContainerHeader&) const = default;
};

/// The GOF chunk: one group of frames, decodable on its own (its packets start with a keyframe).
struct GroupOfFrames {
  uint32_t gof_index = 0;    ///< 0, 1, 2, ... in file order
  uint32_t first_frame = 0;  ///< frame number of the group's first frame
  uint32_t frame_count = 0;  ///< frames in the group, >= 1
  std::vector<uint8_t> transforms;                   ///< per-frame rigid transforms (opaque)
  std::vector<std::vector<std::vector<uint8_t>>> packets;  ///< [stream][packet] bytes (opaque)
  bool operator==(const GroupOfFrames&) const = default;
};

/// One INDX entry: where GOF chunk k starts and which frames it holds.
struct IndexEntry {
  uint64_t offset = 0;  ///< file offset of the GOF chunk's first byte
  uint32_t first_frame = 0;
  uint32_t frame_count = 0;
  bool operator==(const IndexEntry&) const = default;
};

/// One key group of the INDX chunk: a run of groups of frames that share one BASE and MOTN.
struct KeyGroupEntry {
  uint64_t base_offset = 0;    ///< file offset of the key group's BASE chunk, 0 if absent
  uint64_t motion_offset = 0;  ///< file offset of the key group's MOTN chunk, 0 if absent
  uint32_t first_gof = 0;      ///< index of the key group's first GOF
  bool operator==(const KeyGroupEntry&) const = default;
};

/// The INDX chunk. Version 1 stores one key group (its base and motion offsets) implicitly.
struct ContainerIndex {
  std::vector<KeyGroupEntry> key_groups;  ///< at least one; first_gof 0, then increasing
  std::vector<IndexEntry> gofs;
  bool operator==(const ContainerIndex&) const = default;
  /// The key group GOF `gof` belongs to (the last whose first_gof <= gof).
  size_t KeyGroupOfGof(size_t gof) const;
};

/// Builds the key groups of a container from its chunks in file order and enforces their
/// order rules: a key group's BASE and MOTN come at most once each, before its first GOF; a
/// BASE or MOTN after a GOF starts the next key group (format_version 2 only).
class KeyGroupTracker {
 public:
  explicit KeyGroupTracker(uint32_t format_version) : version_(format_version) {
    key_groups_.push_back({});
  }
  /// A BASE or MOTN chunk at `offset`; kCorrupt (prefixed by `context`) when out of order.
  Status AddBaseOrMotion(bool is_base, uint64_t offset, const std::string& context);
  /// A GOF chunk (the next in file order).
  void AddGof() { ++gof_count_; }
  /// The key groups so far (at least one).
  const std::vector<KeyGroupEntry>& key_groups() const { return key_groups_; }

 private:
  uint32_t version_;
  uint32_t gof_count_ = 0;
  std::vector<KeyGroupEntry> key_groups_;
};

/// Largest frame number + 1 a file may reach: every frame count (a GOF's, a key group's, the
/// whole file's) and first_frame + frame_count must fit in a u32.
inline constexpr uint64_t kMaxFrameEnd = UINT32_MAX;
/// True when frames [first_frame, first_frame + frame_count) end at most at kMaxFrameEnd.
inline bool FrameRangeFits(uint32_t first_frame, uint32_t frame_count) {
  return uint64_t{first_frame} + frame_count <= kMaxFrameEnd;
}

/// Checks a header a writer is about to store (rate, codec tags, sizes within the limits).
Status CheckHeader(const ContainerHeader& header);

/// HEAD payload bytes, and back. `context` prefixes decode errors.
std::vector<uint8_t> EncodeHeaderPayload(const ContainerHeader& header);
StatusOr<ContainerHeader> DecodeHeaderPayload(std::span<const uint8_t> payload,
                                              std::string context);

/// GOF payload bytes, and back; decoding checks that the GOF has `stream_count` packet lists.
std::vector<uint8_t> EncodeGofPayload(const GroupOfFrames& gof);
StatusOr<GroupOfFrames> DecodeGofPayload(std::span<const uint8_t> payload, size_t stream_count,
                                         std::string context);
/// Bytes at the start of a GOF payload holding gof_index, first_frame, frame_count.
inline constexpr size_t kGofPrefixSize = 12;

/// INDX payload bytes of `format_version` (1: exactly one key group), and back. Decoding
/// checks that entries are in increasing offset order with contiguous frames, and that every
/// key group but a version-1 file's holds at least one GOF.
StatusOr<std::vector<uint8_t>> EncodeIndexPayload(const ContainerIndex& index,
                                                  uint32_t format_version);
StatusOr<ContainerIndex> DecodeIndexPayload(std::span<const uint8_t> payload,
                                            uint32_t format_version, std::string context);

/// TRLR payload (u64 index_offset), and back.
std::vector<uint8_t> EncodeTrailerPayload(uint64_t index_offset);
StatusOr<uint64_t> DecodeTrailerPayload(std::span<const uint8_t> payload, std::string context);

}  // namespace meshvid

#endif  // MESHVID_FORMAT_PAYLOADS_H_
