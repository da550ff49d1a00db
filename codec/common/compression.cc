#include "codec/common/compression.h"

namespace meshvid {

bool ZstdCanExpandTo(std::size_t compressed_size, std::uint64_t size) {
  // Overflow-safe form of size <= compressed_size * kMaxZstdExpansion.
  return size / kMaxZstdExpansion + (size % kMaxZstdExpansion != 0 ? 1 : 0) <= compressed_size;
}

std::vector<std::uint8_t> SplitBytePlanes(std::span<const std::uint8_t> values_bytes) {
  const std::size_t values = values_bytes.size() / 4;
  std::vector<std::uint8_t> planes(values_bytes.size());
  for (std::size_t i = 0; i < values; ++i) {
    for (std::size_t b = 0; b < 4; ++b) planes[b * values + i] = values_bytes[4 * i + b];
  }
  return planes;
}

std::vector<std::uint8_t> JoinBytePlanes(std::span<const std::uint8_t> planes) {
  const std::size_t values = planes.size() / 4;
  std::vector<std::uint8_t> joined(planes.size());
  for (std::size_t b = 0; b < 4; ++b) {
    for (std::size_t i = 0; i < values; ++i) joined[4 * i + b] = planes[b * values + i];
  }
  return joined;
}

}  // namespace meshvid
