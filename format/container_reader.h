// Random-access reader of .mvid files (seekable file or memory buffer). Open() reads the
// preamble and HEAD, then the TRLR at the end and the INDX it points to, so ReadGof(k) reads
// only GOF k's chunk. When the trailer or index is missing or damaged (e.g. a truncated file)
// it falls back to a forward scan of chunk headers and offers every complete GOF before the cut.
#ifndef MESHVID_FORMAT_CONTAINER_READER_H_
#define MESHVID_FORMAT_CONTAINER_READER_H_

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "format/byte_source.h"
#include "format/payloads.h"
#include "format/status.h"

namespace meshvid {

/// Reads a .mvid container through a ByteSource.
class ContainerReader {
 public:
  /// Opens a container; fails only if the preamble or HEAD chunk is unusable.
  static StatusOr<ContainerReader> Open(std::unique_ptr<ByteSource> source);
  /// Open() over a file.
  static StatusOr<ContainerReader> OpenFile(const std::string& path);
  /// Open() over a copy of `bytes`; `name` appears in error messages.
  static StatusOr<ContainerReader> OpenMemory(std::vector<uint8_t> bytes,
                                              std::string name = "<memory>");

  /// The HEAD chunk.
  const ContainerHeader& header() const { return header_; }
  /// The preamble's format_version (1 or 2).
  uint32_t format_version() const { return format_version_; }
  /// True when GOF locations came from INDX; false when they came from a forward scan.
  bool used_index() const { return used_index_; }
  /// Ok when INDX was used; otherwise why it could not be (missing trailer, bad CRC, ...).
  const Status& index_status() const { return index_status_; }
  /// After a forward scan: ok if it reached TRLR cleanly, else why it stopped (e.g. truncated).
  const Status& scan_status() const { return scan_status_; }

  /// Location and frames of every GOF that can be read (all of them, or those before a cut).
  const std::vector<IndexEntry>& gofs() const { return index_.gofs; }
  size_t gof_count() const { return index_.gofs.size(); }
  /// Frames covered by gofs().
  uint64_t frame_count() const;
  /// The GOF holding `frame` (kNotFound if no readable GOF holds it).
  StatusOr<size_t> FindGof(uint64_t frame) const;

  /// The key groups whose chunks can be read (at least one; a version-1 file has one).
  const std::vector<KeyGroupEntry>& key_groups() const { return index_.key_groups; }
  /// The key group GOF `gof` belongs to.
  size_t KeyGroupOfGof(size_t gof) const { return index_.KeyGroupOfGof(gof); }
  /// GOFs [first, end) of key group `k` (k < key_groups().size()).
  std::pair<size_t, size_t> GofsOfKeyGroup(size_t k) const;

  bool has_base() const { return index_.key_groups[0].base_offset != 0; }
  bool has_motion() const { return index_.key_groups[0].motion_offset != 0; }
  /// The BASE payload of key group `k` (CRC-checked); kNotFound when it has none.
  StatusOr<std::vector<uint8_t>> ReadBase(size_t k = 0);
  /// The MOTN payload of key group `k` (CRC-checked); kNotFound when it has none.
  StatusOr<std::vector<uint8_t>> ReadMotion(size_t k = 0);
  /// GOF `k` (0-based), reading only its chunk; CRC-checked and matched against its index entry.
  StatusOr<GroupOfFrames> ReadGof(size_t k);

  /// The underlying input (e.g. to inspect how many bytes were read).
  ByteSource& source() { return *source_; }

 private:
  explicit ContainerReader(std::unique_ptr<ByteSource> source) : source_(std::move(source)) {}
  /// Reads, CRC-checks and returns the payload of the chunk at `offset`, which must be `type`.
  StatusOr<std::vector<uint8_t>> ReadChunkPayload(uint64_t offset, uint32_t type);
  Status ReadHead();
  Status LoadIndex();
  void ScanChunks();

  std::unique_ptr<ByteSource> source_;
  ContainerHeader header_;
  ContainerIndex index_;
  uint32_t format_version_ = 0;
  uint64_t head_end_ = 0;
  bool used_index_ = false;
  Status index_status_;
  Status scan_status_;
};

}  // namespace meshvid

#endif  // MESHVID_FORMAT_CONTAINER_READER_H_
