#include "tools/io/ply_header.h"

#include <charconv>
#include <utility>

namespace meshvid::io_internal {
namespace {

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Splits a header line into whitespace-separated words.
std::vector<std::string_view> Words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsSpace(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !IsSpace(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

// Text after the first word of `line`, trimmed.
std::string RestAfterFirstWord(std::string_view line, std::string_view first) {
  std::size_t pos = line.find(first);
  pos = (pos == std::string_view::npos) ? line.size() : pos + first.size();
  std::string_view rest = line.substr(pos);
  while (!rest.empty() && IsSpace(rest.front())) rest.remove_prefix(1);
  while (!rest.empty() && IsSpace(rest.back())) rest.remove_suffix(1);
  return std::string(rest);
}

}  // namespace

std::optional<PlyType> ParsePlyType(std::string_view name) {
  if (name == "char" || name == "int8") return PlyType::kInt8;
  if (name == "uchar" || name == "uint8") return PlyType::kUint8;
  if (name == "short" || name == "int16") return PlyType::kInt16;
  if (name == "ushort" || name == "uint16") return PlyType::kUint16;
  if (name == "int" || name == "int32") return PlyType::kInt32;
  if (name == "uint" || name == "uint32") return PlyType::kUint32;
  if (name == "float" || name == "float32") return PlyType::kFloat32;
  if (name == "double" || name == "float64") return PlyType::kFloat64;
  return std::nullopt;
}

int PlyElement::FindProperty(std::string_view property_name) const {
  for (std::size_t i = 0; i < properties.size(); ++i) {
    if (properties[i].name == property_name) return static_cast<int>(i);
  }
  return -1;
}

bool PlyElement::HasFixedBinaryRow() const {
  for (const PlyProperty& p : properties) {
    if (p.is_list) return false;
  }
  return true;
}

std::size_t PlyElement::MinRowBytes(PlyFormat format) const {
  if (format == PlyFormat::kAscii) return 2 * properties.size();  // one digit + separator each
  std::size_t bytes = 0;
  for (const PlyProperty& p : properties) {
    bytes += PlyTypeSize(p.is_list ? p.count_type : p.type);
  }
  return bytes;
}

std::optional<long long> PlyHeader::ObjInfoInt(std::string_view key) const {
  for (const auto& [k, v] : obj_info) {
    if (k != key) continue;
    long long value = 0;
    const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
    if (ec != std::errc() || ptr == v.data()) return std::nullopt;
    return value;
  }
  return std::nullopt;
}

StatusOr<PlyHeader> ParsePlyHeader(std::string_view data, const std::string& name) {
  PlyHeader header;
  std::size_t pos = 0;
  std::size_t line_number = 0;
  bool saw_format = false;
  while (true) {
    if (pos >= data.size()) {
      if (line_number == 0) return CorruptError(name + ": not a PLY file (the file is empty)");
      return CorruptError(name + ": PLY header has no end_header line");
    }
    std::size_t eol = data.find('\n', pos);
    const bool last = eol == std::string_view::npos;
    if (last) eol = data.size();
    std::string_view line = data.substr(pos, eol - pos);
    pos = last ? data.size() : eol + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::vector<std::string_view> words = Words(line);

    if (line_number == 1) {
      if (words.size() != 1 || words[0] != "ply") {
        return CorruptError(name + ": not a PLY file (the first line is not 'ply')");
      }
      continue;
    }
    if (words.empty()) continue;
    const std::string_view keyword = words[0];
    const std::string where = name + ": header line " + std::to_string(line_number) + ": ";
    if (keyword == "comment") continue;
    if (keyword == "obj_info") {
      if (words.size() >= 2) {
        const std::string key(words[1]);
        header.obj_info.emplace_back(key, RestAfterFirstWord(
                                              line.substr(line.find("obj_info") + 8), key));
      }
      continue;
    }
    if (keyword == "format") {
      if (words.size() < 2) return CorruptError(where + "'format' without an encoding");
      if (words[1] == "ascii") {
        header.format = PlyFormat::kAscii;
      } else if (words[1] == "binary_little_endian") {
        header.format = PlyFormat::kBinaryLittleEndian;
      } else if (words[1] == "binary_big_endian") {
        header.format = PlyFormat::kBinaryBigEndian;
      } else {
        return UnsupportedError(where + "unknown PLY format '" + std::string(words[1]) +
                                "' (expected ascii, binary_little_endian or "
                                "binary_big_endian)");
      }
      saw_format = true;
      continue;
    }
    if (keyword == "element") {
      if (words.size() != 3) return CorruptError(where + "expected 'element NAME COUNT'");
      PlyElement element;
      element.name = std::string(words[1]);
      const auto [ptr, ec] =
          std::from_chars(words[2].data(), words[2].data() + words[2].size(), element.count);
      if (ec != std::errc() || ptr != words[2].data() + words[2].size()) {
        return CorruptError(where + "element '" + element.name + "' has an invalid count '" +
                            std::string(words[2]) + "'");
      }
      header.elements.push_back(std::move(element));
      continue;
    }
    if (keyword == "property") {
      if (header.elements.empty()) {
        return CorruptError(where + "'property' before any 'element'");
      }
      PlyProperty property;
      if (words.size() == 5 && words[1] == "list") {
        const auto count_type = ParsePlyType(words[2]);
        const auto item_type = ParsePlyType(words[3]);
        if (!count_type || !item_type) {
          return CorruptError(where + "unknown list type in '" + std::string(line) + "'");
        }
        if (IsFloatType(*count_type)) {
          return CorruptError(where + "list count type must be an integer type");
        }
        property.is_list = true;
        property.count_type = *count_type;
        property.type = *item_type;
        property.name = std::string(words[4]);
      } else if (words.size() == 3) {
        const auto type = ParsePlyType(words[1]);
        if (!type) {
          return CorruptError(where + "unknown property type '" + std::string(words[1]) + "'");
        }
        property.type = *type;
        property.name = std::string(words[2]);
      } else {
        return CorruptError(where + "expected 'property TYPE NAME' or "
                                    "'property list COUNT_TYPE ITEM_TYPE NAME'");
      }
      header.elements.back().properties.push_back(std::move(property));
      continue;
    }
    if (keyword == "end_header") {
      if (!saw_format) return CorruptError(name + ": PLY header has no 'format' line");
      header.body_offset = pos;
      header.body_line = line_number + 1;
      return header;
    }
    return CorruptError(where + "unknown header keyword '" + std::string(keyword) + "'");
  }
}

}  // namespace meshvid::io_internal
