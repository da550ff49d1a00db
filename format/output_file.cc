#include "format/output_file.h"

#include <atomic>
#include <filesystem>
#include <system_error>

#include <unistd.h>

namespace meshvid {
namespace fs = std::filesystem;

Status CreateParentFolders(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) return Status::Ok();
  std::error_code error;
  fs::create_directories(parent, error);
  if (error) {
    return IoError(path + ": cannot create the folder " + parent.string() + ": " +
                   error.message());
  }
  if (!fs::is_directory(parent, error)) {
    return IoError(path + ": " + parent.string() + " exists and is not a folder");
  }
  return Status::Ok();
}

OutputFile::OutputFile(std::string path, std::string temporary)
    : path_(std::move(path)), temporary_(std::move(temporary)) {}

StatusOr<std::unique_ptr<OutputFile>> OutputFile::Open(const std::string& path) {
  if (path.empty()) return InvalidArgumentError("an output path is empty");
  std::error_code error;
  if (fs::is_directory(path, error)) {
    return InvalidArgumentError(path + ": is a folder; give a file name");
  }
  // A device or a pipe (`-o /dev/null`) is written in place: renaming a temporary onto it
  // would replace the device with a plain file.
  const fs::file_status existing = fs::status(path, error);
  if (!error && fs::exists(existing) && !fs::is_regular_file(existing)) {
    std::unique_ptr<OutputFile> file(new OutputFile(path, path));
    file->in_place_ = true;
    file->stream_.open(path, std::ios::binary);
    if (!file->stream_) return IoError(path + ": cannot open for writing (no permission?)");
    return file;
  }
  MESHVID_RETURN_IF_ERROR(CreateParentFolders(path));
  // Unique per process and call, so two writers of one target never share a temporary.
  static std::atomic<unsigned> counter{0};
  const std::string temporary = path + ".partial-" + std::to_string(::getpid()) + "-" +
                                std::to_string(counter.fetch_add(1));
  std::unique_ptr<OutputFile> file(new OutputFile(path, temporary));
  file->stream_.open(temporary, std::ios::binary | std::ios::trunc);
  if (!file->stream_) {
    return IoError(path + ": cannot open for writing (no permission?)");
  }
  return file;
}

OutputFile::~OutputFile() {
  if (committed_ || in_place_) return;
  if (stream_.is_open()) stream_.close();
  std::error_code ignored;
  fs::remove(temporary_, ignored);
}

Status OutputFile::Commit() {
  if (committed_) return InvalidArgumentError(path_ + ": committed twice");
  stream_.flush();
  const bool written = static_cast<bool>(stream_);
  stream_.close();
  if (!written || !stream_) return IoError(path_ + ": write failed (disk full?)");
  if (in_place_) {
    committed_ = true;
    return Status::Ok();
  }
  std::error_code error;
  fs::rename(temporary_, path_, error);
  if (error) return IoError(path_ + ": cannot replace it: " + error.message());
  committed_ = true;
  return Status::Ok();
}

Status WriteFileAtomically(const std::string& path, std::string_view bytes) {
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<OutputFile> file, OutputFile::Open(path));
  file->stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return file->Commit();
}

}  // namespace meshvid
