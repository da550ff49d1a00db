// Checks of option values whose messages name the value and its bound ("--level: -1 is below
// 0"), where CLI11's NonNegativeNumber and PositiveNumber print a range up to the largest
// double.
#ifndef MESHVID_TOOLS_CLI_OPTION_CHECKS_H_
#define MESHVID_TOOLS_CLI_OPTION_CHECKS_H_

#include <CLI/CLI.hpp>

namespace meshvid::cli {

/// A number >= 0.
CLI::Validator AtLeastZero();
/// A number > 0.
CLI::Validator AboveZero();

}  // namespace meshvid::cli

#endif  // MESHVID_TOOLS_CLI_OPTION_CHECKS_H_
