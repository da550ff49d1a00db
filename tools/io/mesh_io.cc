// ReadMesh / WriteMesh: format dispatch by file extension, and whole-file reading.
#include "tools/io/mesh_io.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "format/output_file.h"
#include "tools/io/mesh_io_internal.h"

namespace meshvid {
namespace {

enum class MeshFileType { kPly, kObj, kUnknown };

MeshFileType TypeOf(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".ply") return MeshFileType::kPly;
  if (extension == ".obj") return MeshFileType::kObj;
  return MeshFileType::kUnknown;
}

Status UnknownExtension(const std::string& path) {
  return UnsupportedError(path + ": unknown mesh file extension (expected .ply or .obj)");
}

// Reads the whole file, sized once from its length.
StatusOr<std::string> ReadWholeFile(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return NotFoundError(path + ": no such file");
  if (std::filesystem::is_directory(status)) {
    return InvalidArgumentError(path + ": is a directory, not a mesh file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return IoError(path + ": cannot open for reading (permissions?)");
  return io_internal::ReadAll(in, path);
}

}  // namespace

namespace io_internal {

StatusOr<std::string> ReadAll(std::istream& in, const std::string& name) {
  std::string data;
  const std::istream::pos_type start = in.tellg();
  if (start != std::istream::pos_type(-1) && in.seekg(0, std::ios::end)) {
    const std::istream::pos_type end = in.tellg();
    in.seekg(start);
    if (end != std::istream::pos_type(-1) && end >= start) {
      data.resize(static_cast<std::size_t>(end - start));
      in.read(data.data(), static_cast<std::streamsize>(data.size()));
      data.resize(static_cast<std::size_t>(in.gcount()));
      if (in.bad()) return IoError(name + ": read error");
      return data;
    }
  }
  in.clear();
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) return IoError(name + ": read error");
  return buffer.str();
}

}  // namespace io_internal

StatusOr<TriangleMesh> ReadMesh(const std::string& path) {
  const MeshFileType type = TypeOf(path);
  if (type == MeshFileType::kUnknown) return UnknownExtension(path);
  MESHVID_ASSIGN_OR_RETURN(const std::string data, ReadWholeFile(path));
  if (type == MeshFileType::kPly) return io_internal::ParsePly(data, path);
  return io_internal::ParseObj(data, path);
}

Status WriteMesh(const std::string& path, const TriangleMesh& mesh,
                 const MeshWriteOptions& options) {
  const MeshFileType type = TypeOf(path);
  if (type == MeshFileType::kUnknown) return UnknownExtension(path);
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<OutputFile> out, OutputFile::Open(path));
  Status status = type == MeshFileType::kPly ? WritePly(out->stream(), mesh, options)
                                             : WriteObj(out->stream(), mesh, options);
  if (!status.ok()) return status.WithContext(path);
  return out->Commit();
}

}  // namespace meshvid
