// Progress reporting: long library operations take a callback; the CLI draws it as a bar. And
// the one way the project times its stages.
#ifndef MESHVID_CODEC_COMMON_PROGRESS_H_
#define MESHVID_CODEC_COMMON_PROGRESS_H_

#include <chrono>
#include <functional>
#include <string_view>

namespace meshvid {

/// Called with the stage name and `done` out of `total` units of work. Returning false asks
/// the operation to stop; it then returns a kCancelled Status. May be empty (no reporting).
/// Called from the thread that started the operation only.
using ProgressCallback = std::function<bool(std::string_view stage, long done, long total)>;

/// Invokes `progress` if set; returns false if it asked to cancel.
inline bool ReportProgress(const ProgressCallback& progress, std::string_view stage, long done,
                           long total) {
  return !progress || progress(stage, done, total);
}

/// Seconds from `start` (a std::chrono::steady_clock time) to now.
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_PROGRESS_H_
