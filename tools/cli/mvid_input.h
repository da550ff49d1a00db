// .mvid inputs of the CLI's commands: one rule for partial files (cut or damaged, fewer frames
// readable than the header promises). Every command that reads a .mvid refuses one (exit 1)
// unless given --allow-partial, and then warns that it reads only the readable frames.
#ifndef MESHVID_TOOLS_CLI_MVID_INPUT_H_
#define MESHVID_TOOLS_CLI_MVID_INPUT_H_

#include <CLI/CLI.hpp>
#include <string>

#include "codec/dec/mvid_decoder.h"

namespace meshvid::cli {

/// Adds the --allow-partial flag, with the same help in every command.
void AddAllowPartialFlag(CLI::App* cmd, bool* allow_partial);

/// If the .mvid `path`, opened as `info`, is partial (or its groups hold more frames than its
/// header promises), prints a warning naming the file and the counts on stderr.
void WarnIfPartial(const std::string& path, const MvidInfo& info);

/// The same for an input a command opened through another interface (eval's and render's
/// sources): if `spec` names a .mvid, its counts are read from its container.
void WarnIfPartial(const std::string& spec);

}  // namespace meshvid::cli

#endif  // MESHVID_TOOLS_CLI_MVID_INPUT_H_
