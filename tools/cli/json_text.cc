#include "tools/cli/json_text.h"

#include <cstdio>

#include "format/output_file.h"

namespace meshvid::cli {

std::string DumpJson(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::replace);
}

Status WriteJsonOutput(const std::string& target, const std::string& text) {
  if (target != "-") return WriteFileAtomically(target, text);
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0) {
    return IoError("cannot write the JSON to stdout");
  }
  return Status::Ok();
}

std::string JsonOptionHelp(const std::string& what) {
  return what + " as JSON to this file (- for stdout)";
}

std::string ToValidUtf8(std::string_view text) {
  // nlohmann's replacement is the reference: a string round-tripped through it dumps as is.
  return nlohmann::json::parse(DumpJson(std::string(text))).get<std::string>();
}

}  // namespace meshvid::cli
