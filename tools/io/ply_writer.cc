// PLY writer (binary little-endian or ascii, float32 coordinates, uchar colours) and the stream
// front end of the PLY reader.
#include <bit>
#include <charconv>
#include <cstring>
#include <istream>
#include <ostream>
#include <string>

#include "tools/io/mesh_io.h"
#include "tools/io/mesh_io_internal.h"

namespace meshvid {
namespace {

// Appends `value` as 4 little-endian bytes at `out`.
template <typename T>
char* StoreLittleEndian(T value, char* out) {
  static_assert(sizeof(T) == 4);
  std::memcpy(out, &value, 4);
  if constexpr (std::endian::native == std::endian::big) {
    std::swap(out[0], out[3]);
    std::swap(out[1], out[2]);
  }
  return out + 4;
}

// Appends the shortest text that reads back as exactly `value`.
void AppendFloat(float value, std::string* out) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, result.ptr);
}

void AppendUint(std::uint32_t value, std::string* out) {
  char buffer[16];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, result.ptr);
}

std::string PlyHeaderText(const TriangleMesh& mesh, bool normals, bool colours,
                          PlyEncoding encoding) {
  std::string header = "ply\nformat ";
  header += encoding == PlyEncoding::kAscii ? "ascii" : "binary_little_endian";
  header += " 1.0\ncomment written by meshvid\nelement vertex ";
  header += std::to_string(mesh.positions.size());
  header += "\nproperty float x\nproperty float y\nproperty float z\n";
  if (normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
  if (colours) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header += "element face " + std::to_string(mesh.triangles.size()) +
            "\nproperty list uchar int vertex_indices\nend_header\n";
  return header;
}

}  // namespace

Status WritePly(std::ostream& out, const TriangleMesh& mesh, const MeshWriteOptions& options) {
  MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, "mesh to write as PLY"));
  const bool normals = options.write_normals && mesh.normals.size() == mesh.positions.size();
  const bool colours = options.write_colours && mesh.colours.size() == mesh.positions.size();
  std::string buffer = PlyHeaderText(mesh, normals, colours, options.ply_encoding);
  if (options.ply_encoding == PlyEncoding::kBinaryLittleEndian) {
    const std::size_t header_size = buffer.size();
    const std::size_t vertex_bytes = (normals ? 24 : 12) + (colours ? 3 : 0);
    buffer.resize(header_size + mesh.positions.size() * vertex_bytes +
                  mesh.triangles.size() * 13);
    char* p = buffer.data() + header_size;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      for (int c = 0; c < 3; ++c) p = StoreLittleEndian(mesh.positions[i][c], p);
      if (normals) {
        for (int c = 0; c < 3; ++c) p = StoreLittleEndian(mesh.normals[i][c], p);
      }
      if (colours) {
        for (int c = 0; c < 3; ++c) *p++ = static_cast<char>(mesh.colours[i][c]);
      }
    }
    for (const Triangle& t : mesh.triangles) {
      *p++ = 3;
      for (int c = 0; c < 3; ++c) p = StoreLittleEndian(static_cast<std::int32_t>(t[c]), p);
    }
  } else {
    buffer.reserve(buffer.size() + mesh.positions.size() * (normals ? 80 : 40) +
                   mesh.triangles.size() * 24);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        if (c > 0) buffer += ' ';
        AppendFloat(mesh.positions[i][c], &buffer);
      }
      if (normals) {
        for (int c = 0; c < 3; ++c) {
          buffer += ' ';
          AppendFloat(mesh.normals[i][c], &buffer);
        }
      }
      if (colours) {
        for (int c = 0; c < 3; ++c) {
          buffer += ' ';
          AppendUint(mesh.colours[i][c], &buffer);
        }
      }
      buffer += '\n';
    }
    for (const Triangle& t : mesh.triangles) {
      buffer += '3';
      for (int c = 0; c < 3; ++c) {
        buffer += ' ';
        AppendUint(t[c], &buffer);
      }
      buffer += '\n';
    }
  }
  out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  if (!out) return IoError("writing PLY data failed (disk full or stream closed?)");
  return Status::Ok();
}

StatusOr<TriangleMesh> ReadPly(std::istream& in, const std::string& name) {
  MESHVID_ASSIGN_OR_RETURN(const std::string data, io_internal::ReadAll(in, name));
  return io_internal::ParsePly(data, name);
}

}  // namespace meshvid
