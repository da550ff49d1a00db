// JSON text for the command line's outputs. File names are bytes, not necessarily UTF-8, and
// nlohmann::json refuses to dump a string that is not valid UTF-8 (type_error 316): every
// JSON the commands write goes through here, so such a name is written with U+FFFD in place
// of its bad bytes instead of aborting the command.
#ifndef MESHVID_TOOLS_CLI_JSON_TEXT_H_
#define MESHVID_TOOLS_CLI_JSON_TEXT_H_

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "format/status.h"

namespace meshvid::cli {

/// `j` as JSON text (`indent` < 0: one line), invalid UTF-8 in its strings replaced by U+FFFD.
std::string DumpJson(const nlohmann::json& j, int indent = -1);

/// The machine-readable output of a command given as `--json TARGET`: `text` written to the
/// file TARGET (atomically), or to stdout when TARGET is "-".
Status WriteJsonOutput(const std::string& target, const std::string& text);

/// The help of every command's --json option: what is written, then how TARGET is read.
std::string JsonOptionHelp(const std::string& what);

/// `text` with every byte that is not part of valid UTF-8 replaced by U+FFFD, for strings
/// that other code (a library's JSON writer) dumps.
std::string ToValidUtf8(std::string_view text);

}  // namespace meshvid::cli

#endif  // MESHVID_TOOLS_CLI_JSON_TEXT_H_
