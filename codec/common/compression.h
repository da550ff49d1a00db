// zstd-compressed blocks: the entropy coder of meshvid's motion streams.
#ifndef MESHVID_CODEC_COMMON_COMPRESSION_H_
#define MESHVID_CODEC_COMMON_COMPRESSION_H_

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// Compresses `raw` as one zstd frame at `level` (1..19).
std::vector<std::uint8_t> CompressBlock(std::span<const std::uint8_t> raw, int level = 19);

/// Decompresses one zstd frame that must expand to exactly `expected_size` bytes (the caller
/// knows it from counts it has checked), so a corrupt size never causes a large allocation.
/// `what` names the block in errors.
StatusOr<std::vector<std::uint8_t>> DecompressBlock(std::span<const std::uint8_t> compressed,
                                                    std::size_t expected_size,
                                                    std::string_view what);

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_COMPRESSION_H_
