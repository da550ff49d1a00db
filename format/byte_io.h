// The one bounds-checked little-endian byte reader and writer of the .mvid container.
// Every other format/ file reads and writes raw bytes only through these two classes.
#ifndef MESHVID_FORMAT_BYTE_IO_H_
#define MESHVID_FORMAT_BYTE_IO_H_

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// Reads little-endian values from a span of bytes. Never reads past the end: every read
/// checks the remaining size first and returns a kCorrupt Status naming `what` on shortfall.
class ByteReader {
 public:
  /// `context` prefixes error messages (e.g. "chunk HEAD at offset 8").
  explicit ByteReader(std::span<const uint8_t> data, std::string context = "data")
      : data_(data), context_(std::move(context)) {}

  /// Bytes not yet read.
  size_t remaining() const { return data_.size() - position_; }
  /// Bytes read so far (the offset of the next read within the span).
  size_t position() const { return position_; }
  /// The whole span this reader walks.
  std::span<const uint8_t> data() const { return data_; }

  /// Reads an unsigned 8-, 16-, 32- or 64-bit little-endian integer; `what` names the field.
  StatusOr<uint8_t> ReadU8(std::string_view what);
  StatusOr<uint16_t> ReadU16(std::string_view what);
  StatusOr<uint32_t> ReadU32(std::string_view what);
  StatusOr<uint64_t> ReadU64(std::string_view what);
  /// Returns a view of the next `size` bytes (no copy) and advances past them.
  StatusOr<std::span<const uint8_t>> ReadBytes(uint64_t size, std::string_view what);
  /// Reads a u32 byte length followed by that many bytes, as a string (no encoding check).
  /// Fails when the length exceeds `max_size` or the bytes that remain.
  StatusOr<std::string> ReadSizedString(uint64_t max_size, std::string_view what);
  /// Advances `size` bytes.
  Status Skip(uint64_t size, std::string_view what);
  /// The kCorrupt Status this reader would report for `problem` ("context: problem").
  Status Error(std::string_view problem) const;

 private:
  Status Need(uint64_t size, std::string_view what) const;

  std::span<const uint8_t> data_;
  size_t position_ = 0;
  std::string context_;
};

/// Appends little-endian values to a growable byte buffer.
class ByteWriter {
 public:
  void PutU8(uint8_t value) { bytes_.push_back(value); }
  void PutU16(uint16_t value);
  void PutU32(uint32_t value);
  void PutU64(uint64_t value);
  /// Appends raw bytes.
  void PutBytes(std::span<const uint8_t> bytes);
  /// Appends the four characters of a chunk type or codec tag (must be 4 characters long).
  void PutFourcc(std::string_view fourcc);
  /// Appends a u32 byte length followed by the bytes of `text`.
  void PutSizedString(std::string_view text);
  /// Overwrites 4 bytes at `offset` (which must already be written) with `value`.
  void PatchU32(size_t offset, uint32_t value);

  /// Bytes written so far.
  size_t size() const { return bytes_.size(); }
  const std::vector<uint8_t>& bytes() const { return bytes_; }
  /// Moves the buffer out; the writer is empty afterwards.
  std::vector<uint8_t> Release() { return std::move(bytes_); }

 private:
  std::vector<uint8_t> bytes_;
};

/// Loads a little-endian u32 / u64 from exactly 4 / 8 bytes at `p` (caller checks the size).
uint32_t LoadLittleEndianU32(const uint8_t* p);
uint64_t LoadLittleEndianU64(const uint8_t* p);

/// A span over the bytes of a string (for opaque payloads carried as std::string).
inline std::span<const uint8_t> AsBytes(std::string_view text) {
  return {reinterpret_cast<const uint8_t*>(text.data()), text.size()};
}

}  // namespace meshvid

#endif  // MESHVID_FORMAT_BYTE_IO_H_
