#include "tools/cli/json_text.h"

namespace meshvid::cli {

std::string DumpJson(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::replace);
}

std::string ToValidUtf8(std::string_view text) {
  // nlohmann's replacement is the reference: a string round-tripped through it dumps as is.
  return nlohmann::json::parse(DumpJson(std::string(text))).get<std::string>();
}

}  // namespace meshvid::cli
