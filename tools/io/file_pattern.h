// File patterns with `{frame}` and `{view}` placeholders, e.g. `cap/f{frame:04}_v{view}.ply`,
// so any rig's export can be read (and the simulator's written) without a manifest.
#ifndef MESHVID_TOOLS_IO_FILE_PATTERN_H_
#define MESHVID_TOOLS_IO_FILE_PATTERN_H_

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// A parsed pattern. Placeholders: `{frame}`, `{view}`, each optionally with a zero-padded
/// width, `{frame:04}`. Each may appear at most once; only the file name part may hold them.
class FilePattern {
 public:
  /// Parses `pattern`; fails on unknown or malformed placeholders.
  static StatusOr<FilePattern> Parse(const std::string& pattern);
  /// True if `text` contains a `{frame}` or `{view}` placeholder (so is a pattern, not a path).
  static bool LooksLikePattern(const std::string& text);

  bool has_frame() const { return frame_width_ >= 0; }
  bool has_view() const { return view_width_ >= 0; }
  const std::string& pattern() const { return pattern_; }
  /// The path for frame `frame` and view `view` (a placeholder absent ignores its number).
  std::string Expand(int frame, int view = 0) const;
  /// Lists the existing files that match, as (frame, view) -> path. With a width the number
  /// must have exactly that many digits (or more, if it does not fit); without, any digits.
  StatusOr<std::map<std::pair<int, int>, std::string>> Scan() const;

 private:
  std::string pattern_;
  int frame_width_ = -1;  ///< -1: no {frame}; 0: no padding
  int view_width_ = -1;
};

/// Parses a frame range "A:B" (half-open, frames A..B-1), "A:" (A to the end), ":B" or "N"
/// (the single frame N), clipped to [0, frame_count). Fails if no frame is left or the text is
/// malformed. When an explicit end runs past the last frame and `clipped` is given, it receives
/// a sentence saying what was used instead (callers show it as a warning); otherwise it is
/// cleared.
StatusOr<std::pair<int, int>> ParseFrameRange(const std::string& text, int frame_count,
                                              std::string* clipped = nullptr);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_IO_FILE_PATTERN_H_
