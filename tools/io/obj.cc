// Wavefront OBJ reader and writer: v, vn and f (v, v/vt, v//vn, v/vt/vn, negative indices),
// polygons fan triangulated; everything else (vt, g, o, s, usemtl, mtllib, l...) ignored.
#include <charconv>
#include <cmath>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "tools/io/mesh_io.h"
#include "tools/io/mesh_io_internal.h"

namespace meshvid {
namespace io_internal {
namespace {

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Cuts the next whitespace-separated word off the front of `line`; false when none is left.
bool NextWord(std::string_view* line, std::string_view* word) {
  std::size_t i = 0;
  while (i < line->size() && IsSpace((*line)[i])) ++i;
  std::size_t j = i;
  while (j < line->size() && !IsSpace((*line)[j])) ++j;
  *word = line->substr(i, j - i);
  line->remove_prefix(j);
  return !word->empty();
}

bool ParseFloat(std::string_view text, float* value) {
  if (text.size() > 1 && text[0] == '+') text.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), *value);
  return ec == std::errc() && ptr == text.data() + text.size();
}

// Parses "x y z" (extra values such as w or colours ignored).
bool ParseVector(std::string_view rest, Eigen::Vector3f* v) {
  std::string_view word;
  for (int c = 0; c < 3; ++c) {
    if (!NextWord(&rest, &word) || !ParseFloat(word, &(*v)[c])) return false;
  }
  return true;
}

// One `f` corner: 0-based vertex index and normal index (-1 when absent).
struct Corner {
  std::int64_t vertex = -1;
  std::int64_t normal = -1;
};

// What ParseObj accumulates.
struct ObjContents {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  std::vector<Colour> colours;  // one per `v` line when the first has one
  std::size_t first_v_line = 0;
  std::vector<Triangle> triangles;
  std::vector<std::int64_t> corner_normals;  // 3 per triangle, -1 when the corner has none
  std::int64_t max_vertex = -1;              // largest positive vertex reference, and its line
  std::size_t max_vertex_line = 0;
  std::int64_t max_normal = -1;
  std::size_t max_normal_line = 0;
};

// "NAME: line N: ", the start of an error about line N (built only for an error).
std::string Where(const std::string& name, std::size_t line_number) {
  return name + ": line " + std::to_string(line_number) + ": ";
}

// The colour after a `v` line's coordinates (`v x y z r g b`, channels in [0, 1]): false
// without one (nothing, a `w`, or more than three numbers); an error for a channel outside
// [0, 1] or a word that is not a number.
StatusOr<bool> ParseVertexColour(std::string_view rest, const std::string& name,
                                 std::size_t line_number, Colour* colour) {
  std::string_view word;
  float channels[3];
  int count = 0;
  while (NextWord(&rest, &word)) {
    if (count == 3) return false;  // more than r g b: not a colour this reader knows
    if (!ParseFloat(word, &channels[count])) {
      return CorruptError(Where(name, line_number) + "'" + std::string(word) + "' is not a number");
    }
    ++count;
  }
  if (count != 3) return false;
  for (int c = 0; c < 3; ++c) {
    if (!(channels[c] >= 0.0f && channels[c] <= 1.0f)) {
      return CorruptError(Where(name, line_number) + "vertex colour channel " +
                          std::to_string(channels[c]) + " is outside [0, 1]");
    }
    (*colour)[c] = static_cast<std::uint8_t>(std::lround(channels[c] * 255.0f));
  }
  return true;
}

// Parses the `v` line `line_number` (`rest`: the text after the keyword) for its colour,
// after its position was appended: every `v` line has one or none does.
Status AddVertexColour(std::string_view rest, std::size_t line_number, const std::string& name,
                       ObjContents* obj) {
  std::string_view word;
  for (int c = 0; c < 3; ++c) NextWord(&rest, &word);
  Colour colour;
  MESHVID_ASSIGN_OR_RETURN(const bool has_colour,
                           ParseVertexColour(rest, name, line_number, &colour));
  if (obj->positions.size() == 1) obj->first_v_line = line_number;
  const bool first_had = obj->positions.size() == 1 ? has_colour : !obj->colours.empty();
  if (has_colour != first_had) {
    return CorruptError(Where(name, line_number) +
                        (has_colour ? "a vertex colour, but the 'v' line at line "
                                    : "no vertex colour, but the 'v' line at line ") +
                        std::to_string(obj->first_v_line) +
                        (has_colour ? " has none" : " has one") +
                        ": give every vertex a colour (v x y z r g b) or none");
  }
  if (has_colour) obj->colours.push_back(colour);
  return Status::Ok();
}

// Resolves a 1-based or negative (relative) OBJ index; false for 0 or one before the start.
bool ResolveIndex(std::string_view text, std::int64_t count, std::int64_t* index) {
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size() || value == 0) return false;
  *index = value > 0 ? value - 1 : count + value;
  return *index >= 0;
}

Status ParseFace(std::string_view rest, std::size_t line, const std::string& where,
                 ObjContents* obj) {
  Corner first, previous;
  int corners = 0;
  std::string_view word;
  while (NextWord(&rest, &word)) {
    Corner corner;
    const std::size_t slash = word.find('/');
    const std::string_view v_text = word.substr(0, slash);
    if (!ResolveIndex(v_text, static_cast<std::int64_t>(obj->positions.size()), &corner.vertex)) {
      return CorruptError(where + "invalid vertex index '" + std::string(v_text) + "' (there are " +
                          std::to_string(obj->positions.size()) + " vertices so far)");
    }
    if (slash != std::string_view::npos) {
      const std::size_t slash2 = word.find('/', slash + 1);
      if (slash2 != std::string_view::npos && slash2 + 1 < word.size()) {
        const std::string_view n_text = word.substr(slash2 + 1);
        if (!ResolveIndex(n_text, static_cast<std::int64_t>(obj->normals.size()),
                          &corner.normal)) {
          return CorruptError(where + "invalid normal index '" + std::string(n_text) + "'");
        }
      }
    }
    if (corner.vertex > obj->max_vertex) {
      obj->max_vertex = corner.vertex;
      obj->max_vertex_line = line;
    }
    if (corner.normal > obj->max_normal) {
      obj->max_normal = corner.normal;
      obj->max_normal_line = line;
    }
    if (corners == 0) {
      first = corner;
    } else if (corners >= 2) {
      obj->triangles.emplace_back(static_cast<std::uint32_t>(first.vertex),
                                  static_cast<std::uint32_t>(previous.vertex),
                                  static_cast<std::uint32_t>(corner.vertex));
      obj->corner_normals.insert(obj->corner_normals.end(),
                                 {first.normal, previous.normal, corner.normal});
    }
    previous = corner;
    ++corners;
  }
  if (corners < 3) {
    return CorruptError(where + "face with " + std::to_string(corners) +
                        " vertices; a face needs at least 3");
  }
  return Status::Ok();
}

// Per-vertex normals if the file's vn lines are one per vertex and every face uses them
// consistently (each vertex always with the same vn, or no corner naming a vn); else none.
std::vector<Eigen::Vector3f> ConsistentNormals(const ObjContents& obj) {
  const std::size_t n = obj.positions.size();
  if (obj.normals.size() != n || obj.corner_normals.empty()) return {};
  const bool none = obj.corner_normals.front() < 0;
  std::vector<std::int64_t> map(n, -1);
  for (std::size_t k = 0; k < obj.corner_normals.size(); ++k) {
    const std::int64_t normal = obj.corner_normals[k];
    if ((normal < 0) != none) return {};  // some corners with a normal, some without
    if (none) continue;
    std::int64_t& slot = map[obj.triangles[k / 3][k % 3]];
    if (slot >= 0 && slot != normal) return {};
    slot = normal;
  }
  std::vector<Eigen::Vector3f> normals(n);
  for (std::size_t v = 0; v < n; ++v) {
    normals[v] = obj.normals[map[v] >= 0 ? map[v] : static_cast<std::int64_t>(v)];
  }
  return normals;
}

}  // namespace

StatusOr<TriangleMesh> ParseObj(std::string_view data, const std::string& name) {
  ObjContents obj;
  std::size_t pos = 0;
  std::size_t line_number = 0;
  while (pos < data.size()) {
    std::size_t eol = data.find('\n', pos);
    if (eol == std::string_view::npos) eol = data.size();
    std::string_view line = data.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_number;
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    std::string_view keyword;
    if (!NextWord(&line, &keyword)) continue;
    if (keyword == "v" || keyword == "vn") {
      Eigen::Vector3f v;
      if (!ParseVector(line, &v)) {
        return CorruptError(name + ": line " + std::to_string(line_number) + ": '" +
                            std::string(keyword) + "' needs three numbers");
      }
      if (!v.allFinite()) {
        return CorruptError(name + ": line " + std::to_string(line_number) +
                            ": NaN or infinite value");
      }
      (keyword == "v" ? obj.positions : obj.normals).push_back(v);
      if (keyword == "v") MESHVID_RETURN_IF_ERROR(AddVertexColour(line, line_number, name, &obj));
    } else if (keyword == "f") {
      const std::string where = name + ": line " + std::to_string(line_number) + ": ";
      MESHVID_RETURN_IF_ERROR(ParseFace(line, line_number, where, &obj));
    }
  }
  if (obj.positions.empty()) return CorruptError(name + ": OBJ has no vertices ('v' lines)");
  if (obj.triangles.empty()) return CorruptError(name + ": OBJ has no faces ('f' lines)");
  if (obj.max_vertex >= static_cast<std::int64_t>(obj.positions.size())) {
    return CorruptError(name + ": line " + std::to_string(obj.max_vertex_line) +
                        ": vertex index " + std::to_string(obj.max_vertex + 1) +
                        " out of range (the file has " + std::to_string(obj.positions.size()) +
                        " vertices)");
  }
  if (obj.max_normal >= static_cast<std::int64_t>(obj.normals.size())) {
    return CorruptError(name + ": line " + std::to_string(obj.max_normal_line) +
                        ": normal index " + std::to_string(obj.max_normal + 1) +
                        " out of range (the file has " + std::to_string(obj.normals.size()) +
                        " normals)");
  }
  TriangleMesh mesh;
  mesh.normals = ConsistentNormals(obj);
  mesh.positions = std::move(obj.positions);
  mesh.colours = std::move(obj.colours);
  mesh.triangles = std::move(obj.triangles);
  MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, name));
  return mesh;
}

}  // namespace io_internal

namespace {

void AppendNumber(auto value, std::string* out) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, result.ptr);
}

void AppendVectorLine(const char* keyword, const Eigen::Vector3f& v, std::string* out) {
  *out += keyword;
  for (int c = 0; c < 3; ++c) {
    *out += ' ';
    AppendNumber(v[c], out);
  }
  *out += '\n';
}

}  // namespace

StatusOr<TriangleMesh> ReadObj(std::istream& in, const std::string& name) {
  MESHVID_ASSIGN_OR_RETURN(const std::string data, io_internal::ReadAll(in, name));
  return io_internal::ParseObj(data, name);
}

Status WriteObj(std::ostream& out, const TriangleMesh& mesh, const MeshWriteOptions& options) {
  MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, "mesh to write as OBJ"));
  const bool normals = options.write_normals && mesh.normals.size() == mesh.positions.size();
  const bool colours = options.write_colours && mesh.colours.size() == mesh.positions.size();
  std::string text = "# written by meshvid\n";
  text.reserve(mesh.positions.size() * (35 + (normals ? 35 : 0) + (colours ? 20 : 0)) +
               mesh.triangles.size() * 40);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    AppendVectorLine("v", mesh.positions[i], &text);
    if (colours) {
      // The channels in [0, 1], as `v x y z r g b` readers expect.
      text.pop_back();
      for (int c = 0; c < 3; ++c) {
        text += ' ';
        AppendNumber(mesh.colours[i][c] / 255.0f, &text);
      }
      text += '\n';
    }
  }
  if (normals) {
    for (const auto& n : mesh.normals) AppendVectorLine("vn", n, &text);
  }
  for (const Triangle& t : mesh.triangles) {
    text += 'f';
    for (int c = 0; c < 3; ++c) {
      text += ' ';
      AppendNumber(t[c] + 1, &text);
      if (normals) {
        text += "//";
        AppendNumber(t[c] + 1, &text);
      }
    }
    text += '\n';
  }
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) return IoError("writing OBJ data failed (disk full or stream closed?)");
  return Status::Ok();
}

}  // namespace meshvid
