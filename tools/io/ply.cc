// PLY body reader: ascii and binary (both endiannesses) element rows, vertex positions and
// normals and colours, polygon faces (fan triangulated) and Stanford range grids.
#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "tools/io/mesh_io_internal.h"
#include "tools/io/ply_header.h"
#include "tools/io/ply_range_grid.h"

namespace meshvid::io_internal {
namespace {

// What the reader does with one property of an element.
enum class Role : std::uint8_t {
  kSkip,
  kX,
  kY,
  kZ,
  kNx,
  kNy,
  kNz,
  kRed,
  kGreen,
  kBlue,
  kFaceIndices,
  kGridIndices
};

// Slots of a vertex row's values, one per role up to kBlue.
constexpr int kVertexSlots = static_cast<int>(Role::kBlue) + 1;

// What has been read from the body so far.
struct PlyContents {
  bool has_vertex_element = false;
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  std::vector<Colour> colours;
  std::vector<Triangle> triangles;
  bool has_grid = false;
  std::vector<std::int32_t> grid;  // vertex index per cell, -1 for empty cells
};

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

template <typename T>
T LoadValue(const char* p, bool swap) {
  T value;
  if (!swap) {
    std::memcpy(&value, p, sizeof(T));
  } else {
    char bytes[sizeof(T)];
    for (std::size_t i = 0; i < sizeof(T); ++i) bytes[i] = p[sizeof(T) - 1 - i];
    std::memcpy(&value, bytes, sizeof(T));
  }
  return value;
}

double LoadAsDouble(const char* p, PlyType type, bool swap) {
  switch (type) {
    case PlyType::kInt8: return LoadValue<std::int8_t>(p, swap);
    case PlyType::kUint8: return LoadValue<std::uint8_t>(p, swap);
    case PlyType::kInt16: return LoadValue<std::int16_t>(p, swap);
    case PlyType::kUint16: return LoadValue<std::uint16_t>(p, swap);
    case PlyType::kInt32: return LoadValue<std::int32_t>(p, swap);
    case PlyType::kUint32: return LoadValue<std::uint32_t>(p, swap);
    case PlyType::kFloat32: return LoadValue<float>(p, swap);
    case PlyType::kFloat64: return LoadValue<double>(p, swap);
  }
  return 0;
}

// The vertex colour's properties: red, green and blue (or diffuse_red, ...), all three.
std::optional<std::array<int, 3>> ColourProperties(const PlyElement& e) {
  for (const char* prefix : {"", "diffuse_"}) {
    const std::string p(prefix);
    const std::array<int, 3> found = {e.FindProperty(p + "red"), e.FindProperty(p + "green"),
                                      e.FindProperty(p + "blue")};
    if (found[0] >= 0 && found[1] >= 0 && found[2] >= 0) return found;
  }
  return std::nullopt;
}

// A colour property must be a scalar (any type: its values are checked row by row).
Status CheckColourTypes(const PlyElement& e, const std::string& name) {
  const auto colour = ColourProperties(e);
  if (!colour) return Status::Ok();
  for (const int k : *colour) {
    if (e.properties[k].is_list) {
      return UnsupportedError(name + ": vertex colour property '" + e.properties[k].name +
                              "' is a list; a colour channel is one number");
    }
  }
  return Status::Ok();
}

// The range a colour channel of `type` must lie in, as the errors state it.
const char* ColourRangeText(PlyType type) {
  if (type == PlyType::kUint16) return "a whole number in 0..65535 for a ushort channel";
  if (IsFloatType(type)) return "in [0, 1] for a floating-point channel";
  return "a whole number in 0..255 for an integer channel";
}

// One colour channel as 8 bits: ushort scaled from 16 bits, another integer type taken as
// 0..255, float and double from [0, 1]. False for a value outside its type's range, a
// fraction in an integer channel (an ascii file can hold one) or NaN.
bool ColourChannel(double value, PlyType type, std::uint8_t* channel) {
  if (IsFloatType(type)) {
    if (!(value >= 0.0 && value <= 1.0)) return false;
    *channel = static_cast<std::uint8_t>(std::lround(value * 255.0));
    return true;
  }
  const double most = type == PlyType::kUint16 ? 65535.0 : 255.0;
  if (!(value >= 0.0 && value <= most) || value != std::floor(value)) return false;
  *channel = static_cast<std::uint8_t>(type == PlyType::kUint16 ? std::lround(value / 257.0)
                                                                : std::lround(value));
  return true;
}

// The colour of a vertex row from its values (indexed by Role), the channels' types in
// `types`; an error naming the vertex for a channel outside its type's range.
Status RowColour(const double* values, const std::array<PlyType, 3>& types, const std::string& name,
                 std::uint64_t row, Colour* colour) {
  for (int c = 0; c < 3; ++c) {
    const double value = values[static_cast<int>(Role::kRed) + c];
    if (!ColourChannel(value, types[c], &(*colour)[c])) {
      std::ostringstream text;
      text << value;
      return CorruptError(name + ": vertex " + std::to_string(row) + " has colour channel " +
                          text.str() + ", which must be " + ColourRangeText(types[c]));
    }
  }
  return Status::Ok();
}

// Converts a list count or index to an integer; false if it is not a whole number.
bool ToInteger(double value, std::int64_t* out) {
  if (!std::isfinite(value) || value != std::floor(value) || std::fabs(value) > 9.0e15) {
    return false;
  }
  *out = static_cast<std::int64_t>(value);
  return true;
}

// Row source over a binary body.
class BinarySource {
 public:
  BinarySource(std::string_view data, std::size_t pos, bool swap)
      : data_(data), pos_(pos), swap_(swap) {}

  std::size_t remaining() const { return data_.size() - pos_; }
  const char* cursor() const { return data_.data() + pos_; }
  bool swap() const { return swap_; }
  void Advance(std::size_t bytes) { pos_ += bytes; }
  Status BeginRow(const PlyElement&, std::uint64_t) { return Status::Ok(); }
  Status EndRow(const PlyElement&, std::uint64_t) { return Status::Ok(); }

  bool Scalar(PlyType type, double* value) {
    const std::size_t size = PlyTypeSize(type);
    if (remaining() < size) return Fail("truncated");
    *value = LoadAsDouble(data_.data() + pos_, type, swap_);
    pos_ += size;
    return true;
  }
  bool Integer(PlyType type, std::int64_t* value) {
    double v = 0;
    if (!Scalar(type, &v)) return false;
    return ToInteger(v, value) || Fail("a list count or index is not a whole number");
  }
  bool SkipScalar(PlyType type) { return SkipItems(type, 1); }
  bool SkipItems(PlyType type, std::uint64_t n) {
    const std::size_t size = PlyTypeSize(type);
    if (n > remaining() / size) return Fail("truncated");
    pos_ += n * size;
    return true;
  }
  Status Error(const std::string& name, const PlyElement& e, std::uint64_t row) const {
    if (problem_ == "truncated") {
      return CorruptError(name + ": truncated binary PLY: expected " + std::to_string(e.count) +
                          " " + e.name + " elements, file ends after " + std::to_string(row));
    }
    return CorruptError(name + ": " + e.name + " " + std::to_string(row) + ": " + problem_);
  }

 private:
  bool Fail(const char* problem) {
    problem_ = problem;
    return false;
  }
  std::string_view data_;
  std::size_t pos_;
  bool swap_;
  std::string problem_;
};

// Row source over an ascii body: one element row per line, blank lines skipped.
class AsciiSource {
 public:
  AsciiSource(std::string_view data, std::size_t pos, std::size_t line)
      : data_(data), pos_(pos), next_line_(line) {}

  std::size_t remaining() const { return data_.size() - pos_; }

  Status BeginRow(const PlyElement& e, std::uint64_t row) {
    while (pos_ < data_.size()) {
      std::size_t eol = data_.find('\n', pos_);
      if (eol == std::string_view::npos) eol = data_.size();
      cursor_ = pos_;
      line_end_ = eol;
      line_ = next_line_++;
      pos_ = eol < data_.size() ? eol + 1 : eol;
      SkipSpaces();
      if (cursor_ < line_end_) return Status::Ok();
    }
    return CorruptError(name_ + ": ascii PLY ends early: expected " + std::to_string(e.count) +
                        " " + e.name + " rows, found " + std::to_string(row));
  }
  Status EndRow(const PlyElement& e, std::uint64_t row) {
    SkipSpaces();
    if (cursor_ == line_end_) return Status::Ok();
    problem_ = "more values than the element's " + std::to_string(e.properties.size()) +
               " properties";
    return Error(name_, e, row);
  }
  bool Scalar(PlyType type, double* value) {
    std::string_view token;
    if (!NextToken(&token)) return false;
    const char* end = token.data() + token.size();
    std::from_chars_result result;
    if (type == PlyType::kFloat32) {
      float f = 0;
      result = std::from_chars(token.data(), end, f);
      *value = f;
    } else {
      result = std::from_chars(token.data(), end, *value);
    }
    if (result.ec != std::errc() || result.ptr != end) return Fail("invalid number '" + std::string(token) + "'");
    return true;
  }
  bool Integer(PlyType type, std::int64_t* value) {
    std::string_view token;
    if (!NextToken(&token)) return false;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
    if (ec == std::errc() && ptr == end) return true;
    double d = 0;
    const auto [dptr, dec] = std::from_chars(token.data(), end, d);
    if (dec == std::errc() && dptr == end && ToInteger(d, value)) return true;
    return Fail("invalid integer '" + std::string(token) + "'");
  }
  bool SkipScalar(PlyType) {
    std::string_view token;
    return NextToken(&token);
  }
  bool SkipItems(PlyType, std::uint64_t n) {
    std::string_view token;
    for (std::uint64_t i = 0; i < n; ++i) {
      if (!NextToken(&token)) return false;
    }
    return true;
  }
  Status Error(const std::string& name, const PlyElement& e, std::uint64_t row) const {
    return CorruptError(name + ": line " + std::to_string(line_) + ": " + e.name + " " +
                        std::to_string(row) + ": " + problem_);
  }
  void set_name(const std::string& name) { name_ = name; }

 private:
  void SkipSpaces() {
    while (cursor_ < line_end_ && IsSpace(data_[cursor_])) ++cursor_;
  }
  bool NextToken(std::string_view* token) {
    SkipSpaces();
    if (cursor_ == line_end_) return Fail("too few values on the line");
    std::size_t start = cursor_;
    while (cursor_ < line_end_ && !IsSpace(data_[cursor_])) ++cursor_;
    if (data_[start] == '+' && cursor_ - start > 1) ++start;  // from_chars rejects '+'
    *token = data_.substr(start, cursor_ - start);
    return true;
  }
  bool Fail(std::string problem) {
    problem_ = std::move(problem);
    return false;
  }
  std::string_view data_;
  std::size_t pos_;
  std::size_t next_line_;
  std::size_t cursor_ = 0;
  std::size_t line_end_ = 0;
  std::size_t line_ = 0;
  std::string problem_;
  std::string name_;
};

std::vector<Role> AssignRoles(const PlyElement& e) {
  std::vector<Role> roles(e.properties.size(), Role::kSkip);
  const bool vertex = e.name == "vertex";
  const bool has_normals = vertex && e.FindProperty("nx") >= 0 && e.FindProperty("ny") >= 0 &&
                           e.FindProperty("nz") >= 0;
  const auto colour = vertex ? ColourProperties(e) : std::nullopt;
  if (colour) {
    for (int c = 0; c < 3; ++c) roles[(*colour)[c]] = static_cast<Role>(int(Role::kRed) + c);
  }
  bool face_list_found = false;
  for (std::size_t k = 0; k < e.properties.size(); ++k) {
    const PlyProperty& p = e.properties[k];
    if (vertex && !p.is_list) {
      if (p.name == "x") roles[k] = Role::kX;
      if (p.name == "y") roles[k] = Role::kY;
      if (p.name == "z") roles[k] = Role::kZ;
      if (has_normals && p.name == "nx") roles[k] = Role::kNx;
      if (has_normals && p.name == "ny") roles[k] = Role::kNy;
      if (has_normals && p.name == "nz") roles[k] = Role::kNz;
    } else if (e.name == "face" && p.is_list && !face_list_found &&
               (p.name == "vertex_indices" || p.name == "vertex_index")) {
      roles[k] = Role::kFaceIndices;
      face_list_found = true;
    } else if (e.name == "range_grid" && p.is_list && p.name == "vertex_indices") {
      roles[k] = Role::kGridIndices;
    }
  }
  return roles;
}

// Reads every row of element `e` from `src` into `out`.
template <class Source>
Status ReadElementRows(Source& src, const PlyElement& e, const std::vector<Role>& roles,
                       const std::string& name, PlyContents* out) {
  const bool vertex = e.name == "vertex";
  const bool has_normals = vertex && std::find(roles.begin(), roles.end(), Role::kNx) != roles.end();
  const auto colour = vertex ? ColourProperties(e) : std::nullopt;
  std::array<PlyType, 3> colour_types{};
  if (colour) {
    for (int c = 0; c < 3; ++c) colour_types[c] = e.properties[(*colour)[c]].type;
  }
  // Vertex indices are checked here when the vertices came first (the usual order).
  const std::uint64_t index_limit = out->has_vertex_element
                                        ? out->positions.size()
                                        : std::numeric_limits<std::uint32_t>::max();
  for (std::uint64_t row = 0; row < e.count; ++row) {
    MESHVID_RETURN_IF_ERROR(src.BeginRow(e, row));
    double values[kVertexSlots] = {};
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      const Role role = roles[k];
      if (!p.is_list) {
        const bool ok = role == Role::kSkip ? src.SkipScalar(p.type)
                                            : src.Scalar(p.type, &values[static_cast<int>(role)]);
        if (!ok) return src.Error(name, e, row);
        continue;
      }
      std::int64_t n = 0;
      if (!src.Integer(p.count_type, &n)) return src.Error(name, e, row);
      if (n < 0) {
        return CorruptError(name + ": " + e.name + " " + std::to_string(row) +
                            ": list '" + p.name + "' has negative length " + std::to_string(n));
      }
      if (role == Role::kFaceIndices) {
        if (n < 3) {
          return CorruptError(name + ": face " + std::to_string(row) + " has " +
                              std::to_string(n) + " vertex indices; a face needs at least 3");
        }
        std::uint32_t corner[2] = {0, 0};
        std::uint32_t first = 0;
        for (std::int64_t i = 0; i < n; ++i) {
          std::int64_t index = 0;
          if (!src.Integer(p.type, &index)) return src.Error(name, e, row);
          if (index < 0 || static_cast<std::uint64_t>(index) >= index_limit) {
            return CorruptError(name + ": face " + std::to_string(row) + " uses vertex index " +
                                std::to_string(index) + " out of range (the file has " +
                                std::to_string(out->positions.size()) + " vertices)");
          }
          const auto v = static_cast<std::uint32_t>(index);
          if (i == 0) {
            first = v;
          } else if (i == 1) {
            corner[1] = v;
          } else {
            corner[0] = corner[1];
            corner[1] = v;
            out->triangles.emplace_back(first, corner[0], corner[1]);
          }
        }
      } else if (role == Role::kGridIndices) {
        if (n > 1) {
          return CorruptError(name + ": range_grid cell " + std::to_string(row) + " has " +
                              std::to_string(n) + " vertex indices, expected 0 or 1");
        }
        if (n == 1) {
          std::int64_t index = 0;
          if (!src.Integer(p.type, &index)) return src.Error(name, e, row);
          if (index < 0 || static_cast<std::uint64_t>(index) >= index_limit) {
            return CorruptError(name + ": range_grid cell " + std::to_string(row) +
                                " uses vertex index " + std::to_string(index) +
                                " out of range (the file has " +
                                std::to_string(out->positions.size()) + " vertices)");
          }
          out->grid[row] = static_cast<std::int32_t>(index);
        }
      } else if (!src.SkipItems(p.type, static_cast<std::uint64_t>(n))) {
        return src.Error(name, e, row);
      }
    }
    MESHVID_RETURN_IF_ERROR(src.EndRow(e, row));
    if (vertex) {
      const Eigen::Vector3f position(static_cast<float>(values[1]), static_cast<float>(values[2]),
                                     static_cast<float>(values[3]));
      if (!position.allFinite()) {
        return CorruptError(name + ": vertex " + std::to_string(row) +
                            " has a NaN or infinite coordinate");
      }
      out->positions.push_back(position);
      if (has_normals) {
        out->normals.emplace_back(static_cast<float>(values[4]), static_cast<float>(values[5]),
                                  static_cast<float>(values[6]));
      }
      if (colour) {
        MESHVID_RETURN_IF_ERROR(
            RowColour(values, colour_types, name, row, &out->colours.emplace_back()));
      }
    }
  }
  return Status::Ok();
}

// Fast path for a binary vertex element without lists (CheckCountFits proved it fits).
Status ReadFixedBinaryVertices(BinarySource& src, const PlyElement& e,
                               const std::vector<Role>& roles, const std::string& name,
                               PlyContents* out) {
  struct Field {
    std::size_t offset;
    PlyType type;
    int slot;
  };
  std::vector<Field> fields;
  std::size_t offset = 0;
  bool has_normals = false;
  const auto colour = ColourProperties(e);
  std::array<PlyType, 3> colour_types{};
  for (std::size_t k = 0; k < e.properties.size(); ++k) {
    if (roles[k] != Role::kSkip) fields.push_back({offset, e.properties[k].type, static_cast<int>(roles[k])});
    has_normals = has_normals || roles[k] == Role::kNx;
    if (roles[k] >= Role::kRed && roles[k] <= Role::kBlue) {
      colour_types[int(roles[k]) - int(Role::kRed)] = e.properties[k].type;
    }
    offset += PlyTypeSize(e.properties[k].type);
  }
  const std::size_t stride = offset;
  const char* row = src.cursor();
  const bool swap = src.swap();
  out->positions.resize(e.count);
  if (has_normals) out->normals.resize(e.count);
  if (colour) out->colours.resize(e.count);
  for (std::uint64_t i = 0; i < e.count; ++i, row += stride) {
    double values[kVertexSlots] = {};
    for (const Field& f : fields) values[f.slot] = LoadAsDouble(row + f.offset, f.type, swap);
    Eigen::Vector3f& position = out->positions[i];
    position = Eigen::Vector3d(values[1], values[2], values[3]).cast<float>();
    if (!position.allFinite()) {
      return CorruptError(name + ": vertex " + std::to_string(i) +
                          " has a NaN or infinite coordinate");
    }
    if (has_normals) out->normals[i] = Eigen::Vector3d(values[4], values[5], values[6]).cast<float>();
    if (colour) {
      MESHVID_RETURN_IF_ERROR(RowColour(values, colour_types, name, i, &out->colours[i]));
    }
  }
  src.Advance(e.count * stride);
  return Status::Ok();
}

// Fast path for a binary face element whose only property is the index list.
Status ReadBinaryFaceLists(BinarySource& src, const PlyElement& e, const std::string& name,
                           std::uint64_t vertex_limit, PlyContents* out) {
  const PlyProperty& list = e.properties[0];
  const std::size_t count_size = PlyTypeSize(list.count_type);
  const std::size_t index_size = PlyTypeSize(list.type);
  const bool swap = src.swap();
  const char* p = src.cursor();
  const char* const end = p + src.remaining();
  for (std::uint64_t row = 0; row < e.count; ++row) {
    if (static_cast<std::size_t>(end - p) < count_size) return CorruptError(
        name + ": truncated binary PLY: expected " + std::to_string(e.count) + " " + e.name +
        " elements, file ends after " + std::to_string(row));
    std::int64_t n = 0;
    if (!ToInteger(LoadAsDouble(p, list.count_type, swap), &n) || n < 3) {
      return CorruptError(name + ": face " + std::to_string(row) + " has " +
                          std::to_string(n) + " vertex indices; a face needs at least 3");
    }
    p += count_size;
    if (static_cast<std::uint64_t>(end - p) / index_size < static_cast<std::uint64_t>(n)) {
      return CorruptError(name + ": truncated binary PLY: expected " + std::to_string(e.count) +
                          " " + e.name + " elements, file ends after " + std::to_string(row));
    }
    std::uint32_t corner[3];
    for (std::int64_t i = 0; i < n; ++i, p += index_size) {
      std::int64_t index = 0;
      if (!ToInteger(LoadAsDouble(p, list.type, swap), &index) || index < 0 ||
          static_cast<std::uint64_t>(index) >= vertex_limit) {
        return CorruptError(name + ": face " + std::to_string(row) + " uses vertex index " +
                            std::to_string(index) + " out of range (the file has " +
                            std::to_string(out->positions.size()) + " vertices)");
      }
      corner[i < 2 ? i : 2] = static_cast<std::uint32_t>(index);
      if (i >= 2) {
        out->triangles.emplace_back(corner[0], corner[1], corner[2]);
        corner[1] = corner[2];
      }
    }
  }
  src.Advance(static_cast<std::size_t>(p - src.cursor()));
  return Status::Ok();
}

// Checks that `e.count` rows can fit in what is left of the file, before anything is reserved.
Status CheckCountFits(const PlyElement& e, PlyFormat format, std::size_t remaining,
                      const std::string& name) {
  const std::size_t min_row = e.MinRowBytes(format);
  if (min_row == 0 || e.count == 0) return Status::Ok();
  // An ascii file's last row may end without its newline; a binary row has no slack.
  const std::uint64_t slack = format == PlyFormat::kAscii ? 1 : 0;
  const std::uint64_t max_rows = (static_cast<std::uint64_t>(remaining) + slack) / min_row;
  if (e.count <= max_rows) return Status::Ok();
  if (format == PlyFormat::kAscii) {
    return CorruptError(name + ": ascii PLY ends early: the header declares " +
                        std::to_string(e.count) + " " + e.name + " rows but only " +
                        std::to_string(remaining) + " bytes follow");
  }
  return CorruptError(name + ": truncated binary PLY: expected " + std::to_string(e.count) + " " +
                      e.name + " elements, file ends after " +
                      (e.HasFixedBinaryRow() ? "" : "at most ") +
                      std::to_string(remaining / min_row));
}

template <class Source>
Status ReadBody(Source& src, const PlyHeader& header, const std::string& name,
                PlyContents* out) {
  for (const PlyElement& e : header.elements) {
    MESHVID_RETURN_IF_ERROR(CheckCountFits(e, header.format, src.remaining(), name));
    const std::vector<Role> roles = AssignRoles(e);
    const bool skipped = std::all_of(roles.begin(), roles.end(),
                                     [](Role r) { return r == Role::kSkip; });
    if (e.name == "vertex") {
      if (out->has_vertex_element) return CorruptError(name + ": two 'vertex' elements");
      if (e.FindProperty("x") < 0 || e.FindProperty("y") < 0 || e.FindProperty("z") < 0) {
        return CorruptError(name + ": the vertex element lacks an x, y or z property");
      }
      if (e.count > std::numeric_limits<std::int32_t>::max()) {
        return UnsupportedError(name + ": " + std::to_string(e.count) +
                                " vertices exceed the 32-bit index range");
      }
      MESHVID_RETURN_IF_ERROR(CheckColourTypes(e, name));
      out->positions.reserve(e.count);
    } else if (e.name == "face" && !skipped) {
      out->triangles.reserve(out->triangles.size() + e.count);
    } else if (e.name == "range_grid" && !skipped) {
      out->has_grid = true;
      out->grid.assign(e.count, -1);
    }
    bool done = false;
    if constexpr (std::is_same_v<Source, BinarySource>) {
      if (e.HasFixedBinaryRow()) {  // CheckCountFits proved that the rows fit
        if (e.name == "vertex") {
          MESHVID_RETURN_IF_ERROR(ReadFixedBinaryVertices(src, e, roles, name, out));
        } else {
          src.Advance(e.count * e.MinRowBytes(header.format));  // nothing to read: bulk skip
        }
        done = true;
      } else if (e.properties.size() == 1 && roles[0] == Role::kFaceIndices) {
        const std::uint64_t limit = out->has_vertex_element
                                        ? out->positions.size()
                                        : std::numeric_limits<std::uint32_t>::max();
        MESHVID_RETURN_IF_ERROR(ReadBinaryFaceLists(src, e, name, limit, out));
        done = true;
      }
    }
    if (!done) MESHVID_RETURN_IF_ERROR(ReadElementRows(src, e, roles, name, out));
    if (e.name == "vertex") out->has_vertex_element = true;
  }
  return Status::Ok();
}

}  // namespace

StatusOr<TriangleMesh> ParsePly(std::string_view data, const std::string& name) {
  MESHVID_ASSIGN_OR_RETURN(const PlyHeader header, ParsePlyHeader(data, name));
  PlyContents contents;
  if (header.format == PlyFormat::kAscii) {
    AsciiSource src(data, header.body_offset, header.body_line);
    src.set_name(name);
    MESHVID_RETURN_IF_ERROR(ReadBody(src, header, name, &contents));
  } else {
    const bool big = header.format == PlyFormat::kBinaryBigEndian;
    BinarySource src(data, header.body_offset, big != (std::endian::native == std::endian::big));
    MESHVID_RETURN_IF_ERROR(ReadBody(src, header, name, &contents));
  }
  if (!contents.has_vertex_element) return CorruptError(name + ": PLY has no 'vertex' element");
  if (contents.positions.empty()) return CorruptError(name + ": PLY has no vertices");
  TriangleMesh mesh;
  if (contents.triangles.empty() && contents.has_grid) {
    MESHVID_ASSIGN_OR_RETURN(mesh, MeshStanfordRangeGrid(header, contents.positions,
                                                         contents.colours, contents.grid, name));
  } else {
    if (contents.triangles.empty()) return CorruptError(name + ": PLY has no faces");
    mesh.positions = std::move(contents.positions);
    mesh.normals = std::move(contents.normals);
    mesh.colours = std::move(contents.colours);
    mesh.triangles = std::move(contents.triangles);
  }
  MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, name));
  return mesh;
}

}  // namespace meshvid::io_internal
