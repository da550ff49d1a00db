// Numbers in the JSON files the tools write and read (eval, decode, info and encode summaries,
// bench records): one writer and one reader, so every file spells non-finite values alike and
// every reader treats a missing figure alike.
#ifndef MESHVID_TOOLS_JSON_JSON_NUMBER_H_
#define MESHVID_TOOLS_JSON_JSON_NUMBER_H_

#include <nlohmann/json.hpp>

namespace meshvid {

/// `value` for JSON: +-inf (an exact frame's PSNR) becomes the string "inf"/"-inf", NaN (not
/// measured) null, anything else the number.
nlohmann::json JsonNumber(double value);

/// A number written by JsonNumber(): "inf"/"-inf" are +-inf, null is NaN. Anything else (another
/// string, an object) throws std::invalid_argument naming `key`: the file is not what it
/// claims to be.
double JsonNumberValue(const nlohmann::json& value, const char* key);

/// The number at `key` of object `j` (JsonNumberValue). A missing key is NaN: a figure the file
/// does not hold (an older file, a figure not measured), never a measured 0.
double JsonNumber(const nlohmann::json& j, const char* key);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_JSON_JSON_NUMBER_H_
