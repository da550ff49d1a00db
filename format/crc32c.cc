#include "format/crc32c.h"

#include <array>
#include <cstring>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define MESHVID_CRC32C_X86 1
#include <nmmintrin.h>
#endif

namespace meshvid {
namespace {

constexpr uint32_t kReflectedPolynomial = 0x82F63B78u;

using SliceTables = std::array<std::array<uint32_t, 256>, 8>;

constexpr SliceTables MakeTables() {
  SliceTables tables{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t crc = i;
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ ((crc & 1u) ? kReflectedPolynomial : 0u);
    tables[0][i] = crc;
  }
  for (uint32_t i = 0; i < 256; ++i) {
    for (int t = 1; t < 8; ++t) {
      tables[t][i] = (tables[t - 1][i] >> 8) ^ tables[0][tables[t - 1][i] & 0xFFu];
    }
  }
  return tables;
}

constexpr SliceTables kTables = MakeTables();

// Inner loop on the raw (pre-inverted) register value.
uint32_t UpdatePortable(uint32_t crc, const uint8_t* p, size_t n) {
  while (n >= 8) {
    // Little-endian assembly of the next 8 bytes, independent of the host byte order.
    const uint32_t lo = crc ^ (static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
                               static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24);
    crc = kTables[7][lo & 0xFF] ^ kTables[6][(lo >> 8) & 0xFF] ^ kTables[5][(lo >> 16) & 0xFF] ^
          kTables[4][lo >> 24] ^ kTables[3][p[4]] ^ kTables[2][p[5]] ^ kTables[1][p[6]] ^
          kTables[0][p[7]];
    p += 8;
    n -= 8;
  }
  while (n-- > 0) crc = (crc >> 8) ^ kTables[0][(crc ^ *p++) & 0xFFu];
  return crc;
}

#ifdef MESHVID_CRC32C_X86
__attribute__((target("sse4.2"))) uint32_t UpdateHardware(uint32_t crc, const uint8_t* p,
                                                           size_t n) {
  uint64_t crc64 = crc;
  while (n >= 8) {
    uint64_t word;
    std::memcpy(&word, p, 8);  // x86 is little-endian
    crc64 = _mm_crc32_u64(crc64, word);
    p += 8;
    n -= 8;
  }
  crc = static_cast<uint32_t>(crc64);
  while (n-- > 0) crc = _mm_crc32_u8(crc, *p++);
  return crc;
}

bool DetectHardware() { return __builtin_cpu_supports("sse4.2"); }
#else
bool DetectHardware() { return false; }
#endif

}  // namespace

bool Crc32cUsesHardware() {
  static const bool has_hardware = DetectHardware();
  return has_hardware;
}

uint32_t Crc32cExtendPortable(uint32_t crc, std::span<const uint8_t> data) {
  return ~UpdatePortable(~crc, data.data(), data.size());
}

uint32_t Crc32cExtend(uint32_t crc, std::span<const uint8_t> data) {
#ifdef MESHVID_CRC32C_X86
  if (Crc32cUsesHardware()) return ~UpdateHardware(~crc, data.data(), data.size());
#endif
  return Crc32cExtendPortable(crc, data);
}

uint32_t Crc32c(std::span<const uint8_t> data) { return Crc32cExtend(0, data); }

}  // namespace meshvid
