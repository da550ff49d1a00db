// PLY header model and parser (internal to the mesh I/O module): the element and property
// declarations, the body encoding and the obj_info lines of a PLY file.
#ifndef MESHVID_TOOLS_IO_PLY_HEADER_H_
#define MESHVID_TOOLS_IO_PLY_HEADER_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "format/status.h"

namespace meshvid::io_internal {

/// Scalar types a PLY property may have.
enum class PlyType : std::uint8_t { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

/// Size of one value of `type` in binary encodings.
inline std::size_t PlyTypeSize(PlyType type) {
  constexpr std::size_t kSizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return kSizes[static_cast<int>(type)];
}

/// True for the two floating-point types.
inline bool IsFloatType(PlyType type) {
  return type == PlyType::kFloat32 || type == PlyType::kFloat64;
}

/// Parses a PLY type name (both the classic "uchar" and the sized "uint8" spellings).
std::optional<PlyType> ParsePlyType(std::string_view name);

/// How the body of a PLY file is encoded.
enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

/// One property of an element: a scalar, or a list with its own count type.
struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyType type = PlyType::kFloat32;        ///< the scalar type, or the list item type
  PlyType count_type = PlyType::kUint8;    ///< list count type (lists only)
};

/// One element declaration ("element vertex 42" and its properties).
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;

  /// Index of the property called `name`, or -1.
  int FindProperty(std::string_view property_name) const;
  /// True if no property is a list, so every binary row has the same size.
  bool HasFixedBinaryRow() const;
  /// Bytes of the smallest possible row (lists counted as empty) in `format`.
  std::size_t MinRowBytes(PlyFormat format) const;
};

/// A parsed PLY header.
struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  /// obj_info lines as (first word, rest of the line), e.g. ("num_cols", "512").
  std::vector<std::pair<std::string, std::string>> obj_info;
  std::size_t body_offset = 0;  ///< byte offset of the first body byte
  std::size_t body_line = 0;    ///< 1-based line number of the first body line (ascii)

  /// The obj_info value for `key` parsed as an integer, if present and numeric.
  std::optional<long long> ObjInfoInt(std::string_view key) const;
};

/// Parses the header at the start of `data`. Errors (kCorrupt or kUnsupported) start with
/// `name` and say what is wrong: not a PLY, unknown format or type, missing end_header.
StatusOr<PlyHeader> ParsePlyHeader(std::string_view data, const std::string& name);

}  // namespace meshvid::io_internal

#endif  // MESHVID_TOOLS_IO_PLY_HEADER_H_
