#include "format/chunk.h"

#include <cstdio>

#include "format/byte_io.h"
#include "format/crc32c.h"

namespace meshvid {

std::string FourccName(uint32_t type) {
  std::string name;
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((type >> (8 * i)) & 0xFF);
    if (c < 0x20 || c > 0x7E) {
      char hex[16];
      std::snprintf(hex, sizeof(hex), "0x%08x", type);
      return hex;
    }
    name.push_back(c);
  }
  return name;
}

std::string ChunkContext(std::string_view source, uint32_t type, uint64_t offset) {
  return std::string(source) + ": chunk '" + FourccName(type) + "' at offset " +
         std::to_string(offset);
}

std::vector<uint8_t> EncodePreamble() {
  ByteWriter writer;
  writer.PutFourcc(kMvidMagic);
  writer.PutU32(kMvidFormatVersion);
  return writer.Release();
}

StatusOr<uint32_t> CheckPreamble(std::span<const uint8_t> bytes, std::string_view source) {
  const std::string name(source);
  if (bytes.size() < kPreambleSize) {
    return CorruptError(name + ": too short for a .mvid file (" + std::to_string(bytes.size()) +
                        " bytes; the preamble alone is " + std::to_string(kPreambleSize) + ")");
  }
  if (std::string_view(reinterpret_cast<const char*>(bytes.data()), 4) != kMvidMagic) {
    return CorruptError(name + ": not a .mvid file (the first 4 bytes are not \"MVID\")");
  }
  const uint32_t version = LoadLittleEndianU32(bytes.data() + 4);
  if (version < kMvidOldestReadableVersion || version > kMvidFormatVersion) {
    return UnsupportedError(name + ": .mvid format_version " + std::to_string(version) +
                            " is not supported (this build reads versions " +
                            std::to_string(kMvidOldestReadableVersion) + " to " +
                            std::to_string(kMvidFormatVersion) + ")");
  }
  return version;
}

std::vector<uint8_t> EncodeChunk(uint32_t type, uint32_t flags, std::span<const uint8_t> payload) {
  ByteWriter writer;
  writer.PutU32(type);
  writer.PutU32(flags);
  writer.PutU64(payload.size());
  writer.PutBytes(payload);
  writer.PutU32(Crc32c(writer.bytes()));
  return writer.Release();
}

StatusOr<ChunkHeader> ParseChunkHeader(std::span<const uint8_t> bytes, uint64_t offset,
                                       uint64_t max_payload_size, std::string_view source) {
  ByteReader reader(bytes, std::string(source) + ": chunk header at offset " +
                               std::to_string(offset));
  ChunkHeader header;
  MESHVID_ASSIGN_OR_RETURN(header.type, reader.ReadU32("type"));
  MESHVID_ASSIGN_OR_RETURN(header.flags, reader.ReadU32("flags"));
  MESHVID_ASSIGN_OR_RETURN(header.payload_size, reader.ReadU64("payload_size"));
  const std::string context = ChunkContext(source, header.type, offset);
  if ((header.flags & ~kChunkKnownFlags) != 0) {
    return CorruptError(context + ": reserved flag bits set (flags 0x" + [&] {
      char hex[16];
      std::snprintf(hex, sizeof(hex), "%08x", header.flags);
      return std::string(hex);
    }() + ")");
  }
  if (header.payload_size > max_payload_size) {
    return CorruptError(context + ": payload_size " + std::to_string(header.payload_size) +
                        " exceeds the " + std::to_string(max_payload_size) +
                        " bytes the input can hold (truncated or corrupt file)");
  }
  return header;
}

Status VerifyChunkCrc(std::span<const uint8_t> chunk, uint64_t offset, std::string_view source) {
  const uint32_t type = chunk.size() >= 4 ? LoadLittleEndianU32(chunk.data()) : 0;
  if (chunk.size() < kChunkHeaderSize + kChunkCrcSize) {
    return CorruptError(ChunkContext(source, type, offset) + ": truncated chunk");
  }
  const size_t covered = chunk.size() - kChunkCrcSize;
  const uint32_t stored = LoadLittleEndianU32(chunk.data() + covered);
  const uint32_t computed = Crc32c(chunk.first(covered));
  if (stored != computed) {
    char text[96];
    std::snprintf(text, sizeof(text), ": crc32c mismatch (stored 0x%08x, computed 0x%08x)",
                  stored, computed);
    return CorruptError(ChunkContext(source, type, offset) + text);
  }
  return Status::Ok();
}

}  // namespace meshvid
