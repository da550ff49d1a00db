// Chunk framing of the .mvid container: the file preamble (magic + version) and the chunk
// layout  type(4) flags(u32) payload_size(u64) payload crc32c(u32), CRC over type..payload.
// See spec/mvid-container.md for the normative description; names here match the spec.
#ifndef MESHVID_FORMAT_CHUNK_H_
#define MESHVID_FORMAT_CHUNK_H_

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// The four bytes every .mvid file starts with.
inline constexpr std::string_view kMvidMagic = "MVID";
/// The container version this code writes (2: key groups, each with its own BASE and MOTN).
inline constexpr uint32_t kMvidFormatVersion = 2;
/// The oldest container version this code reads (1: one BASE and MOTN for the whole file).
inline constexpr uint32_t kMvidOldestReadableVersion = 1;
/// magic(4) + format_version(u32).
inline constexpr size_t kPreambleSize = 8;
/// type(4) + flags(u32) + payload_size(u64).
inline constexpr size_t kChunkHeaderSize = 16;
/// The crc32c field after the payload.
inline constexpr size_t kChunkCrcSize = 4;

/// The u32 value of a four-character code as stored little-endian ("HEAD" -> 'H' first).
constexpr uint32_t Fourcc(const char (&code)[5]) {
  return static_cast<uint32_t>(static_cast<uint8_t>(code[0])) |
         static_cast<uint32_t>(static_cast<uint8_t>(code[1])) << 8 |
         static_cast<uint32_t>(static_cast<uint8_t>(code[2])) << 16 |
         static_cast<uint32_t>(static_cast<uint8_t>(code[3])) << 24;
}

/// Chunk types of version 1.
inline constexpr uint32_t kChunkHead = Fourcc("HEAD");     ///< header: streams, rate, metadata
inline constexpr uint32_t kChunkBase = Fourcc("BASE");     ///< base mesh bytes (opaque)
inline constexpr uint32_t kChunkMotion = Fourcc("MOTN");   ///< segments/weights bytes (opaque)
inline constexpr uint32_t kChunkGof = Fourcc("GOF ");      ///< one group of frames
inline constexpr uint32_t kChunkIndex = Fourcc("INDX");    ///< offsets of BASE, MOTN, GOFs
inline constexpr uint32_t kChunkTrailer = Fourcc("TRLR");  ///< index_offset, last in the file

/// flags bit 0: a reader that does not know the chunk type may skip the chunk. Unknown types
/// without this bit make the file unsupported. All other bits are reserved and must be 0.
inline constexpr uint32_t kChunkFlagSkippable = 1u;
/// The flag bits version 1 defines.
inline constexpr uint32_t kChunkKnownFlags = kChunkFlagSkippable;

/// Size of the TRLR chunk (header + u64 index_offset + crc): a reader finds it at
/// file_size - kTrailerChunkSize.
inline constexpr size_t kTrailerChunkSize = kChunkHeaderSize + 8 + kChunkCrcSize;

/// Printable form of a chunk type: "HEAD", or "0x1234abcd" when not printable ASCII.
std::string FourccName(uint32_t type);

/// The fixed part that starts every chunk.
struct ChunkHeader {
  uint32_t type = 0;
  uint32_t flags = 0;
  uint64_t payload_size = 0;
  /// Header + payload + crc.
  uint64_t chunk_size() const { return kChunkHeaderSize + payload_size + kChunkCrcSize; }
};

/// The 8-byte preamble "MVID" + format_version.
std::vector<uint8_t> EncodePreamble();
/// Checks magic and version of the first kPreambleSize bytes and returns the format_version
/// (kCorrupt if short or the magic is wrong, kUnsupported for a version this build does not
/// read). `source` names the file in messages.
StatusOr<uint32_t> CheckPreamble(std::span<const uint8_t> bytes, std::string_view source);

/// A whole chunk: header, payload and crc32c over header + payload.
std::vector<uint8_t> EncodeChunk(uint32_t type, uint32_t flags, std::span<const uint8_t> payload);

/// Parses the kChunkHeaderSize bytes of a chunk header found at file `offset`. Rejects
/// reserved flag bits and a payload_size above `max_payload_size` (the bytes the input can
/// still hold, or a stated limit for streams) before anything is allocated.
StatusOr<ChunkHeader> ParseChunkHeader(std::span<const uint8_t> bytes, uint64_t offset,
                                       uint64_t max_payload_size, std::string_view source);

/// Verifies the crc32c of a whole chunk (header + payload + crc bytes) found at `offset`.
Status VerifyChunkCrc(std::span<const uint8_t> chunk, uint64_t offset, std::string_view source);

/// "file.mvid: chunk GOF  at offset 1234" style context for messages.
std::string ChunkContext(std::string_view source, uint32_t type, uint64_t offset);

}  // namespace meshvid

#endif  // MESHVID_FORMAT_CHUNK_H_
