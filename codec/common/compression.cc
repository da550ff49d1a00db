#include "codec/common/compression.h"

#include <string>

#include <zstd.h>

namespace meshvid {

std::vector<std::uint8_t> CompressBlock(std::span<const std::uint8_t> raw, int level) {
  std::vector<std::uint8_t> out(ZSTD_compressBound(raw.size()));
  const std::size_t size = ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), level);
  // Compression into a ZSTD_compressBound buffer cannot fail for valid levels.
  out.resize(ZSTD_isError(size) ? 0 : size);
  return out;
}

StatusOr<std::vector<std::uint8_t>> DecompressBlock(std::span<const std::uint8_t> compressed,
                                                    std::size_t expected_size,
                                                    std::string_view what) {
  const unsigned long long content_size =
      ZSTD_getFrameContentSize(compressed.data(), compressed.size());
  if (content_size == ZSTD_CONTENTSIZE_ERROR) {
    return CorruptError(std::string(what) + ": not a zstd frame");
  }
  if (content_size != ZSTD_CONTENTSIZE_UNKNOWN && content_size != expected_size) {
    return CorruptError(std::string(what) + ": expands to " + std::to_string(content_size) +
                        " bytes, expected " + std::to_string(expected_size));
  }
  std::vector<std::uint8_t> out(expected_size);
  const std::size_t size =
      ZSTD_decompress(out.data(), out.size(), compressed.data(), compressed.size());
  if (ZSTD_isError(size)) {
    return CorruptError(std::string(what) + ": " + ZSTD_getErrorName(size));
  }
  if (size != expected_size) {
    return CorruptError(std::string(what) + ": expands to " + std::to_string(size) +
                        " bytes, expected " + std::to_string(expected_size));
  }
  return out;
}

}  // namespace meshvid
