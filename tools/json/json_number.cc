#include "tools/json/json_number.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace meshvid {

nlohmann::json JsonNumber(double value) {
  if (std::isnan(value)) return nullptr;
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return value;
}

double JsonNumberValue(const nlohmann::json& value, const char* key) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (value.is_number()) return value.get<double>();
  if (value.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (value.is_string()) {
    const std::string& s = value.get_ref<const std::string&>();
    if (s == "inf") return kInf;
    if (s == "-inf") return -kInf;
  }
  throw std::invalid_argument(std::string("'") + key + "' is not a number");
}

double JsonNumber(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it == j.end() ? std::numeric_limits<double>::quiet_NaN() : JsonNumberValue(*it, key);
}

}  // namespace meshvid
