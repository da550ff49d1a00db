// Internal to tools/io: how the capture readers (manifest, pattern, Stanford .conf) fill a
// CaptureSequence. Not a public interface; include only from tools/io/capture*.cc.
#ifndef MESHVID_TOOLS_IO_CAPTURE_BUILDER_H_
#define MESHVID_TOOLS_IO_CAPTURE_BUILDER_H_

#include <memory>
#include <string>
#include <vector>

#include "tools/io/capture.h"

namespace meshvid {

/// Builds CaptureSequences; the one friend of CaptureSequence.
class CaptureSequenceBuilder {
 public:
  /// Reads a manifest.json (capture_manifest.cc).
  static StatusOr<std::unique_ptr<CaptureSequence>> FromManifest(const std::string& path);
  /// Scans a `{frame}`/`{view}` file pattern.
  static StatusOr<std::unique_ptr<CaptureSequence>> FromPattern(const std::string& pattern);
  /// Reads a Stanford `.conf` file.
  static StatusOr<std::unique_ptr<CaptureSequence>> FromConf(const std::string& path);
  /// Assembles a capture and checks that depth images have intrinsics and that colour
  /// images go with depth images; `source` names the input in messages. `poses` may be empty
  /// (identity); `colour_paths` empty, or shaped as `paths` with "" for no colour image.
  static StatusOr<std::unique_ptr<CaptureSequence>> Make(
      const std::string& source, CaptureInfo info, std::vector<std::vector<std::string>> paths,
      std::vector<Eigen::Isometry3d> poses,
      std::vector<std::vector<std::string>> colour_paths = {});
};

/// "v0", "v1", ...: the name of a view that has none.
std::string DefaultViewName(int index);

/// True if `path` names a PNG depth image (by extension, case-insensitive).
bool IsDepthImagePath(const std::string& path);

/// `relative` resolved against the folder of `anchor_file` (unchanged if absolute).
std::string ResolveBesides(const std::string& anchor_file, const std::string& relative);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_IO_CAPTURE_BUILDER_H_
