// Checks of option values whose messages name the value and its bound ("--level: -1 is below
// 0"), where CLI11's NonNegativeNumber and PositiveNumber print a range up to the largest
// double.
#ifndef MESHVID_TOOLS_CLI_OPTION_CHECKS_H_
#define MESHVID_TOOLS_CLI_OPTION_CHECKS_H_

#include <CLI/CLI.hpp>
#include <string>
#include <utility>

#include "format/status.h"

namespace meshvid::cli {

/// A number >= 0.
CLI::Validator AtLeastZero();
/// A number > 0.
CLI::Validator AboveZero();

/// The frames `--frames TEXT` selects of `frame_count` (see ParseFrameRange). A range that
/// runs past the end is clipped with a warning on stderr (every command follows this one
/// rule); one that selects no frame is an error naming --frames.
StatusOr<std::pair<int, int>> FramesOption(const std::string& text, int frame_count);

}  // namespace meshvid::cli

#endif  // MESHVID_TOOLS_CLI_OPTION_CHECKS_H_
