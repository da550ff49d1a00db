// Library-level validation of a .mvid file: walks every chunk, checks every CRC, the chunk
// order rules, every payload this layer understands, and INDX/TRLR against the chunks actually
// present. Shared by `meshvid info --check`, the tests and the fuzzers.
#ifndef MESHVID_FORMAT_VALIDATE_H_
#define MESHVID_FORMAT_VALIDATE_H_

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "format/byte_source.h"
#include "format/payloads.h"
#include "format/status.h"

namespace meshvid {

/// What Validate found about one chunk.
struct ChunkReport {
  uint64_t offset = 0;        ///< file offset of the chunk's first byte
  std::string type;           ///< FourccName of the type
  uint32_t flags = 0;
  uint64_t payload_size = 0;
  bool crc_ok = false;
};

/// The outcome of validating a container.
struct ValidationReport {
  std::vector<ChunkReport> chunks;   ///< every chunk whose header could be read, in file order
  bool header_ok = false;            ///< preamble and HEAD are valid
  ContainerHeader header;            ///< HEAD contents when header_ok
  uint32_t gof_count = 0;            ///< GOF chunks that decoded
  uint64_t frame_count = 0;          ///< frames in those GOFs
  uint32_t key_group_count = 0;      ///< key groups (runs of GOFs sharing a BASE), from INDX
  bool has_index = false;            ///< INDX and TRLR present and CRC-valid
  bool index_consistent = false;     ///< INDX and TRLR agree with the chunks present
  std::vector<std::string> errors;   ///< every problem found, in file order; empty when valid

  bool ok() const { return errors.empty(); }
  /// Ok, or kCorrupt with the first error and the number of others.
  Status ToStatus() const;
  /// Multi-line human-readable summary (one line per chunk, then the errors).
  std::string ToText() const;
};

/// Validates the container read through `source`. Reads each chunk once, in bounded pieces
/// (never more than one chunk, and never more than the input holds).
ValidationReport ValidateContainer(ByteSource& source);
/// Validates a container held in memory.
ValidationReport ValidateContainer(std::span<const uint8_t> bytes,
                                   std::string_view name = "<memory>");
/// Validates a file; kNotFound / kIoError only if it cannot be opened.
StatusOr<ValidationReport> ValidateContainerFile(const std::string& path);

}  // namespace meshvid

#endif  // MESHVID_FORMAT_VALIDATE_H_
