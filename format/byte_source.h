// Random-access inputs for the seekable ContainerReader: a file or a memory buffer.
#ifndef MESHVID_FORMAT_BYTE_SOURCE_H_
#define MESHVID_FORMAT_BYTE_SOURCE_H_

#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// A seekable input of known size.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  /// Total size in bytes.
  virtual uint64_t size() const = 0;
  /// Reads `out.size()` bytes at `offset`; fails (kCorrupt / kIoError) if they are not all there.
  virtual Status ReadAt(uint64_t offset, std::span<uint8_t> out) = 0;
  /// Name used in error messages (the file path, or "<memory>").
  virtual const std::string& name() const = 0;
};

/// A ByteSource over bytes it owns.
class MemorySource : public ByteSource {
 public:
  explicit MemorySource(std::vector<uint8_t> bytes, std::string name = "<memory>")
      : bytes_(std::move(bytes)), name_(std::move(name)) {}
  uint64_t size() const override { return bytes_.size(); }
  Status ReadAt(uint64_t offset, std::span<uint8_t> out) override;
  const std::string& name() const override { return name_; }

 private:
  std::vector<uint8_t> bytes_;
  std::string name_;
};

/// A ByteSource over a file opened for reading.
class FileSource : public ByteSource {
 public:
  /// Opens `path`; kNotFound / kIoError when it cannot be opened or sized.
  static StatusOr<std::unique_ptr<FileSource>> Open(const std::string& path);
  ~FileSource() override;
  uint64_t size() const override { return size_; }
  Status ReadAt(uint64_t offset, std::span<uint8_t> out) override;
  const std::string& name() const override { return path_; }

 private:
  FileSource(std::FILE* file, uint64_t size, std::string path)
      : file_(file), size_(size), path_(std::move(path)) {}
  std::FILE* file_;
  uint64_t size_;
  std::string path_;
};

/// Reads a whole file into memory (kNotFound / kIoError on failure).
StatusOr<std::vector<uint8_t>> ReadWholeFile(const std::string& path);

}  // namespace meshvid

#endif  // MESHVID_FORMAT_BYTE_SOURCE_H_
