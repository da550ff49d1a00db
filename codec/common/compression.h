// zstd-compressed blocks: the entropy coder of meshvid's motion streams.
#ifndef MESHVID_CODEC_COMMON_COMPRESSION_H_
#define MESHVID_CODEC_COMMON_COMPRESSION_H_

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// The most bytes one byte of a zstd frame can expand to. A zstd block (RFC 8878) regenerates
/// at most 128 KiB (ZSTD_BLOCKSIZE_MAX) and costs at least 4 bytes (a 3-byte header and, for
/// an RLE block, the byte it repeats), so no frame expands more than 128 KiB / 4 = 32768-fold.
inline constexpr std::uint64_t kMaxZstdExpansion = 32768;

/// Whether a zstd frame of `compressed_size` bytes can expand to `size` bytes at all
/// (size <= compressed_size * kMaxZstdExpansion): a count from a file that needs more is
/// corrupt, and is rejected before anything is allocated for it.
bool ZstdCanExpandTo(std::size_t compressed_size, std::uint64_t size);

/// Little-endian u32 values (`values_bytes`, 4 bytes each) as byte planes: every value's
/// lowest byte, then every second byte, and so on. zstd finds longer runs in the planes of
/// small values (their zero high bytes together): the transform payloads' byte order.
std::vector<std::uint8_t> SplitBytePlanes(std::span<const std::uint8_t> values_bytes);

/// The inverse of SplitBytePlanes: byte planes back to little-endian u32 values.
std::vector<std::uint8_t> JoinBytePlanes(std::span<const std::uint8_t> planes);

/// Compresses `raw` as one zstd frame at `level` (1..19).
std::vector<std::uint8_t> CompressBlock(std::span<const std::uint8_t> raw, int level = 19);

/// Decompresses `compressed`, which must be exactly one zstd frame expanding to exactly
/// `expected_size` bytes (the caller knows the size from counts in the file). Nothing is
/// allocated for a size that `compressed` cannot expand to (more than kMaxZstdExpansion
/// times its size), and the output grows only as the frame actually produces bytes, so a
/// corrupt count or a frame that ends early fails with kCorrupt after allocating about what
/// the frame holds, whatever `expected_size` says. The frame may declare a window of up to
/// max(8 MiB, expected_size) bytes (what a streaming decoder allocates for it); a larger one
/// is refused. `what` names the block in errors.
StatusOr<std::vector<std::uint8_t>> DecompressBlock(std::span<const std::uint8_t> compressed,
                                                    std::size_t expected_size,
                                                    std::string_view what);

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_COMPRESSION_H_
