// One way to write an output file: parent folders are created, bytes go to a temporary file
// beside the target, and the target appears only when the whole file is written. A failed or
// abandoned write never leaves a truncated file (or a stray temporary) behind. A target that
// exists and is not a regular file (a device such as /dev/null, a pipe) is written in place.
#ifndef MESHVID_FORMAT_OUTPUT_FILE_H_
#define MESHVID_FORMAT_OUTPUT_FILE_H_

#include <fstream>
#include <memory>
#include <string>
#include <string_view>

#include "format/status.h"

namespace meshvid {

/// A file being written atomically. Open() creates the missing parent folders and a temporary
/// file; stream() takes the bytes; Commit() flushes and renames the temporary onto the target.
/// Destroyed without a successful Commit(), the temporary is removed and the target untouched.
class OutputFile {
 public:
  /// Starts writing `path`. Fails (kInvalidArgument) when `path` is empty or names an existing
  /// folder, (kIoError) when a parent folder cannot be created or the temporary opened.
  static StatusOr<std::unique_ptr<OutputFile>> Open(const std::string& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Where the bytes go (seekable: a writer may come back to patch a header).
  std::ostream& stream() { return stream_; }
  /// The target path, as given to Open().
  const std::string& path() const { return path_; }
  /// The temporary file the bytes go to until Commit(): a caller may read it back (after
  /// flushing stream()) to check what it wrote before the target appears.
  const std::string& temporary_path() const { return temporary_; }
  /// Closes the temporary and renames it onto path(); kIoError if a write failed (disk full).
  Status Commit();
  /// Whether the bytes go straight to path() (a device or a pipe): no temporary to read back
  /// (temporary_path() is path()) and nothing to rename.
  bool in_place() const { return in_place_; }

 private:
  OutputFile(std::string path, std::string temporary);
  std::string path_;
  std::string temporary_;
  std::ofstream stream_;
  bool committed_ = false;
  bool in_place_ = false;
};

/// Writes `bytes` to `path` through an OutputFile (parents created, atomic replace).
Status WriteFileAtomically(const std::string& path, std::string_view bytes);

/// Creates the parent folders of `path` (nothing to do for a bare file name).
Status CreateParentFolders(const std::string& path);

}  // namespace meshvid

#endif  // MESHVID_FORMAT_OUTPUT_FILE_H_
