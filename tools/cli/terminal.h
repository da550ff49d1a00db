// Terminal output of the CLI: error reporting, byte counts and the one progress bar every
// command uses.
#ifndef MESHVID_TOOLS_CLI_TERMINAL_H_
#define MESHVID_TOOLS_CLI_TERMINAL_H_

#include <chrono>
#include <cstddef>
#include <string>
#include <string_view>

#include "codec/common/progress.h"
#include "format/status.h"

namespace meshvid::cli {

/// Prints "meshvid: <status>" to stderr and returns the exit code for it (1).
int ReportError(const Status& status);

/// "1 key group", "3 key groups": a count and its noun (`plural` defaults to noun + "s").
std::string Count(std::size_t n, std::string_view noun, std::string_view plural = {});

/// A byte count as the commands print it: "12.3 kB" (1 kB = 1000 bytes).
std::string Kilobytes(double bytes);

/// Draws progress on stderr: a redrawn bar with rate and ETA on a terminal, an occasional
/// plain line at most every 5 seconds otherwise (logs, CI), nothing if quiet.
class ProgressBar {
 public:
  explicit ProgressBar(bool quiet = false);
  ~ProgressBar();
  /// A ProgressCallback drawing into this bar; the bar must outlive it.
  ProgressCallback Callback();
  /// Ends the current line, if a bar is drawn.
  void Finish();
  /// Prints `line` on stderr above the bar (a terminal's bar is erased and redrawn at the
  /// next update), unless quiet.
  void Message(std::string_view line);

 private:
  void Draw(std::string_view stage, long done, long total);
  bool quiet_;
  bool tty_;
  bool drawn_ = false;
  std::string stage_;
  std::chrono::steady_clock::time_point stage_start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace meshvid::cli

#endif  // MESHVID_TOOLS_CLI_TERMINAL_H_
