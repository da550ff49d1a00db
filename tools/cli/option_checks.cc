#include "tools/cli/option_checks.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "tools/io/file_pattern.h"

namespace meshvid::cli {
namespace {

/// The check of a number against 0: at least 0 (`allow_zero`) or above it.
CLI::Validator AgainstZero(bool allow_zero) {
  return CLI::Validator(
      [allow_zero](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end == nullptr || *end != '\0') return "'" + text + "' is not a number";
        if (allow_zero ? !(value >= 0) : !(value > 0)) {
          return text + (allow_zero ? " is below 0" : " is not above 0");
        }
        return {};
      },
      allow_zero ? "NONNEGATIVE" : "POSITIVE");
}

}  // namespace

CLI::Validator AtLeastZero() { return AgainstZero(true); }
CLI::Validator AboveZero() { return AgainstZero(false); }

StatusOr<std::pair<int, int>> FramesOption(const std::string& text, int frame_count) {
  std::string clipped;
  StatusOr<std::pair<int, int>> range = ParseFrameRange(text, frame_count, &clipped);
  if (!range.ok()) return range.status().WithContext("--frames");
  if (!clipped.empty()) std::fprintf(stderr, "meshvid: warning: --frames: %s\n", clipped.c_str());
  return range;
}

}  // namespace meshvid::cli
