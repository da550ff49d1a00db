// Deliberately damaged .mvid files built from the golden file, for the bad-input tests of the
// codec and the command line. Header-only: each test executable that needs them includes it.
#ifndef MESHVID_TESTS_MVID_MUTANTS_H_
#define MESHVID_TESTS_MVID_MUTANTS_H_

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "codec/common/compression.h"
#include "format/byte_io.h"
#include "format/crc32c.h"
#include "format/status.h"

namespace meshvid::testing {

/// A zstd frame (RFC 8878) holding `content` in raw blocks, with no Frame_Content_Size field
/// (so a decoder cannot learn the size before decompressing) and a 128 KiB window.
inline std::vector<std::uint8_t> ZstdFrameWithoutContentSize(
    std::span<const std::uint8_t> content) {
  constexpr std::size_t kBlockMax = 128 * 1024;
  // Magic 0xFD2FB528; Frame_Header_Descriptor 0 (no content size, not single-segment, no
  // checksum, no dictionary); Window_Descriptor 0x38 (exponent 7: 2^17 bytes).
  std::vector<std::uint8_t> frame = {0x28, 0xB5, 0x2F, 0xFD, 0x00, 0x38};
  std::size_t at = 0;
  do {
    const std::size_t size = std::min(kBlockMax, content.size() - at);
    const bool last = at + size == content.size();
    // Block_Header: Last_Block (bit 0), Block_Type 0 = raw (bits 1-2), Block_Size (bits 3-23).
    const std::uint32_t header = (last ? 1u : 0u) | static_cast<std::uint32_t>(size << 3);
    for (int i = 0; i < 3; ++i) frame.push_back(static_cast<std::uint8_t>(header >> (8 * i)));
    frame.insert(frame.end(), content.begin() + at, content.begin() + at + size);
    at += size;
  } while (at < content.size());
  return frame;
}

/// One chunk: type, flags 0, payload_size, payload, CRC32C of all that.
inline std::vector<std::uint8_t> MutantChunk(std::string_view type,
                                             std::span<const std::uint8_t> payload) {
  ByteWriter chunk;
  chunk.PutFourcc(type);
  chunk.PutU32(0);
  chunk.PutU64(payload.size());
  chunk.PutBytes(payload);
  const std::uint32_t crc = Crc32c(chunk.bytes());
  chunk.PutU32(crc);
  return chunk.Release();
}

/// `file` with its HEAD chunk's frame_count set to `frame_count` (the golden file's is 0,
/// unknown) and the chunk's CRC recomputed.
inline std::vector<std::uint8_t> WithHeaderFrameCount(std::span<const std::uint8_t> file,
                                                     std::uint32_t frame_count) {
  // HEAD is the first chunk, after the 8-byte preamble; frame_count follows the frame rate's
  // numerator and denominator. The CRC covers the chunk header and payload.
  constexpr std::size_t kHead = 8, kFrameCountAt = kHead + 16 + 8;
  std::vector<std::uint8_t> out(file.begin(), file.end());
  for (int i = 0; i < 4; ++i) {
    out.at(kFrameCountAt + i) = static_cast<std::uint8_t>(frame_count >> (8 * i));
  }
  const std::size_t end = kHead + 16 + LoadLittleEndianU64(out.data() + kHead + 8);
  const std::uint32_t crc = Crc32c(std::span<const std::uint8_t>(out).subspan(kHead, end - kHead));
  for (int i = 0; i < 4; ++i) out.at(end + i) = static_cast<std::uint8_t>(crc >> (8 * i));
  return out;
}

/// `file` (a version-1 .mvid whose last GOF is followed by INDX and TRLR, as the golden
/// file) with its last group claiming `frame_count` frames everywhere a count is stored:
/// the GOF chunk, the transform block of its side information and its index entry. The
/// transforms' zstd frame is rewritten without its content-size field (holding the group's
/// true transforms) and every changed chunk's CRC is recomputed, so only the counts are
/// wrong. The packets are unchanged.
inline StatusOr<std::vector<std::uint8_t>> WithHugeLastGroup(std::span<const std::uint8_t> file,
                                                            std::uint32_t frame_count) {
  constexpr std::size_t kPreamble = 8, kChunkHeader = 16, kCrc = 4;
  // Chunk offsets by type, walking the chunk headers.
  std::size_t last_gof = 0, index = 0;
  for (std::size_t at = kPreamble; at + kChunkHeader <= file.size();) {
    const std::string type(file.begin() + at, file.begin() + at + 4);
    if (type == "GOF ") last_gof = at;
    if (type == "INDX") index = at;
    at += kChunkHeader + LoadLittleEndianU64(file.data() + at + 8) + kCrc;
  }
  if (last_gof == 0 || index == 0) return CorruptError("mutant: no GOF or INDX chunk");

  // GOF payload: gof_index, first_frame, frame_count, transforms_size, transforms, streams.
  const std::span<const std::uint8_t> gof = file.subspan(
      last_gof + kChunkHeader, LoadLittleEndianU64(file.data() + last_gof + 8));
  ByteReader reader(gof, "mutant GOF");
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t gof_index, reader.ReadU32("gof_index"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t first_frame, reader.ReadU32("first_frame"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t frames, reader.ReadU32("frame_count"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t side_size, reader.ReadU32("transforms_size"));
  MESHVID_ASSIGN_OR_RETURN(const std::span<const std::uint8_t> side,
                           reader.ReadBytes(side_size, "transforms"));
  const std::span<const std::uint8_t> streams = gof.subspan(reader.position());

  // Side information: version, packing, minimum, step, video_config, then the transform
  // block: frame_count, segment_count, zstd(frames x segments x 24).
  ByteReader side_reader(side, "mutant side information");
  MESHVID_RETURN_IF_ERROR(side_reader.Skip(10, "version, packing, range"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t config_size, side_reader.ReadU32("config size"));
  MESHVID_RETURN_IF_ERROR(side_reader.Skip(config_size, "video_config"));
  const std::size_t counts_at = side_reader.position();
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t stored_frames, side_reader.ReadU32("frames"));
  MESHVID_ASSIGN_OR_RETURN(const std::uint32_t segments, side_reader.ReadU32("segments"));
  if (stored_frames != frames) return CorruptError("mutant: inconsistent frame counts");
  MESHVID_ASSIGN_OR_RETURN(
      const std::vector<std::uint8_t> transforms,
      DecompressBlock(side.subspan(side_reader.position()), std::size_t{frames} * segments * 24,
                      "mutant transforms"));

  ByteWriter new_side;
  new_side.PutBytes(side.first(counts_at));
  new_side.PutU32(frame_count);
  new_side.PutU32(segments);
  new_side.PutBytes(ZstdFrameWithoutContentSize(transforms));
  ByteWriter new_gof;
  new_gof.PutU32(gof_index);
  new_gof.PutU32(first_frame);
  new_gof.PutU32(frame_count);
  new_gof.PutU32(static_cast<std::uint32_t>(new_side.bytes().size()));
  new_gof.PutBytes(new_side.bytes());
  new_gof.PutBytes(streams);

  // INDX (version 1): base_offset, motion_offset, gof_count, entries of (offset,
  // first_frame, frame_count); the last entry's frame_count ends the payload.
  std::vector<std::uint8_t> new_index(
      file.begin() + index + kChunkHeader,
      file.begin() + index + kChunkHeader + LoadLittleEndianU64(file.data() + index + 8));
  if (new_index.size() < 4) return CorruptError("mutant: INDX too short");
  for (int i = 0; i < 4; ++i) {
    new_index[new_index.size() - 4 + i] = static_cast<std::uint8_t>(frame_count >> (8 * i));
  }

  std::vector<std::uint8_t> out(file.begin(), file.begin() + last_gof);
  const std::vector<std::uint8_t> gof_chunk = MutantChunk("GOF ", new_gof.bytes());
  out.insert(out.end(), gof_chunk.begin(), gof_chunk.end());
  const std::uint64_t index_offset = out.size();
  const std::vector<std::uint8_t> index_chunk = MutantChunk("INDX", new_index);
  out.insert(out.end(), index_chunk.begin(), index_chunk.end());
  ByteWriter trailer;
  trailer.PutU64(index_offset);
  const std::vector<std::uint8_t> trailer_chunk = MutantChunk("TRLR", trailer.bytes());
  out.insert(out.end(), trailer_chunk.begin(), trailer_chunk.end());
  return out;
}

}  // namespace meshvid::testing

#endif  // MESHVID_TESTS_MVID_MUTANTS_H_
