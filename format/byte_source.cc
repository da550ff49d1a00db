#include "format/byte_source.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace meshvid {

Status MemorySource::ReadAt(uint64_t offset, std::span<uint8_t> out) {
  if (offset > bytes_.size() || out.size() > bytes_.size() - offset) {
    return CorruptError(name_ + ": read of " + std::to_string(out.size()) + " bytes at offset " +
                        std::to_string(offset) + " runs past the end (" +
                        std::to_string(bytes_.size()) + " bytes)");
  }
  if (!out.empty()) std::memcpy(out.data(), bytes_.data() + offset, out.size());
  return Status::Ok();
}

StatusOr<std::unique_ptr<FileSource>> FileSource::Open(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return NotFoundError(path + ": no such file");
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return IoError(path + ": cannot read the file size: " + ec.message());
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return IoError(path + ": cannot open: " + std::strerror(errno));
  return std::unique_ptr<FileSource>(new FileSource(file, size, path));
}

FileSource::~FileSource() { std::fclose(file_); }

Status FileSource::ReadAt(uint64_t offset, std::span<uint8_t> out) {
  if (offset > size_ || out.size() > size_ - offset) {
    return CorruptError(path_ + ": read of " + std::to_string(out.size()) + " bytes at offset " +
                        std::to_string(offset) + " runs past the end (" + std::to_string(size_) +
                        " bytes)");
  }
  if (out.empty()) return Status::Ok();
  if (fseeko(file_, static_cast<off_t>(offset), SEEK_SET) != 0) {
    return IoError(path_ + ": cannot seek to offset " + std::to_string(offset) + ": " +
                   std::strerror(errno));
  }
  if (std::fread(out.data(), 1, out.size(), file_) != out.size()) {
    return IoError(path_ + ": short read of " + std::to_string(out.size()) + " bytes at offset " +
                   std::to_string(offset) + " (file changed while reading?)");
  }
  return Status::Ok();
}

StatusOr<std::vector<uint8_t>> ReadWholeFile(const std::string& path) {
  MESHVID_ASSIGN_OR_RETURN(auto source, FileSource::Open(path));
  std::vector<uint8_t> bytes(source->size());
  MESHVID_RETURN_IF_ERROR(source->ReadAt(0, bytes));
  return bytes;
}

}  // namespace meshvid
