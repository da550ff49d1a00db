// CRC32C (Castagnoli, polynomial 0x1EDC6F41 reflected 0x82F63B78), the checksum of every
// .mvid chunk. Same parameters as iSCSI (RFC 3720) and ext4: initial value and final xor
// 0xFFFFFFFF, bits reflected.
#ifndef MESHVID_FORMAT_CRC32C_H_
#define MESHVID_FORMAT_CRC32C_H_

#include <cstdint>
#include <span>

namespace meshvid {

/// CRC32C of `data`.
uint32_t Crc32c(std::span<const uint8_t> data);

/// Continues a CRC32C: Crc32cExtend(Crc32c(a), b) == Crc32c(a followed by b).
/// Crc32cExtend(0, data) == Crc32c(data).
uint32_t Crc32cExtend(uint32_t crc, std::span<const uint8_t> data);

/// The portable table-driven (slicing-by-8) implementation, whatever the CPU supports.
/// Exposed so tests can compare it with the hardware path.
uint32_t Crc32cExtendPortable(uint32_t crc, std::span<const uint8_t> data);

/// True when Crc32cExtend uses the SSE4.2 crc32 instruction on this machine.
bool Crc32cUsesHardware();

}  // namespace meshvid

#endif  // MESHVID_FORMAT_CRC32C_H_
