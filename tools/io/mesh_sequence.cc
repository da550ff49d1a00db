// MeshSequence sources: template OBJ + .pc2, a folder of mesh files, a {frame} pattern, and a
// single mesh file.
#include "tools/io/mesh_sequence.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>
#include <utility>
#include <vector>

#include "tools/io/file_pattern.h"
#include "tools/io/mesh_io.h"
#include "tools/io/pc2.h"

namespace meshvid {
namespace {

namespace fs = std::filesystem;

/// Lower-case extension with its dot ("" if none).
std::string LowerExtension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool IsMeshFile(const fs::path& path) {
  const std::string extension = LowerExtension(path);
  return extension == ".obj" || extension == ".ply";
}

/// A template mesh animated by a .pc2 point cache: every frame has the template's triangles.
/// The .pc2 sampleRate is the frame *step* in the exporter's timeline (usually 1), not frames
/// per second, so the frame rate is the caller's.
class Pc2MeshSequence : public MeshSequence {
 public:
  Pc2MeshSequence(std::string obj_path, std::string pc2_path, TriangleMesh mesh,
                  std::unique_ptr<Pc2Reader> reader, double frame_rate)
      : obj_path_(std::move(obj_path)),
        pc2_path_(std::move(pc2_path)),
        template_(std::move(mesh)),
        reader_(std::move(reader)),
        frame_rate_(frame_rate) {
    template_.normals.clear();  // the template's normals do not fit the deformed frames
  }

  int frame_count() const override { return reader_->header().num_samples; }
  double frame_rate() const override { return frame_rate_; }
  bool fixed_connectivity() const override { return true; }
  std::string description() const override {
    return obj_path_ + " + " + pc2_path_ + " (" + std::to_string(frame_count()) + " frames, " +
           std::to_string(template_.vertex_count()) + " vertices)";
  }

  StatusOr<TriangleMesh> Frame(int t) override {
    if (t < 0 || t >= frame_count()) {
      return InvalidArgumentError(description() + ": frame " + std::to_string(t) +
                                  " is out of range");
    }
    MESHVID_ASSIGN_OR_RETURN(std::vector<Eigen::Vector3f> positions, reader_->ReadFrame(t));
    TriangleMesh mesh;
    mesh.positions = std::move(positions);
    mesh.triangles = template_.triangles;
    mesh.colours = template_.colours;  // colour rides each vertex through the animation
    MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, pc2_path_ + " frame " + std::to_string(t)));
    return mesh;
  }

 private:
  std::string obj_path_;
  std::string pc2_path_;
  TriangleMesh template_;
  std::unique_ptr<Pc2Reader> reader_;
  double frame_rate_;
};

/// One mesh file per frame, each read when asked for.
class FileListMeshSequence : public MeshSequence {
 public:
  FileListMeshSequence(std::string description, std::vector<std::string> paths, double frame_rate)
      : description_(std::move(description)), paths_(std::move(paths)), frame_rate_(frame_rate) {}

  int frame_count() const override { return static_cast<int>(paths_.size()); }
  double frame_rate() const override { return frame_rate_; }
  /// Unknown in general (each file has its own triangles); trivially true for one file.
  bool fixed_connectivity() const override { return paths_.size() == 1; }
  std::string description() const override { return description_; }

  StatusOr<TriangleMesh> Frame(int t) override {
    if (t < 0 || t >= frame_count()) {
      return InvalidArgumentError(description_ + ": frame " + std::to_string(t) +
                                  " is out of range (" + std::to_string(frame_count()) +
                                  " frames)");
    }
    return ReadMesh(paths_[t]);
  }

 private:
  std::string description_;
  std::vector<std::string> paths_;
  double frame_rate_;
};

StatusOr<std::unique_ptr<MeshSequence>> OpenPc2Sequence(const std::string& obj_path,
                                                        const std::string& pc2_path,
                                                        double frame_rate) {
  MESHVID_ASSIGN_OR_RETURN(TriangleMesh mesh, ReadMesh(obj_path));
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<Pc2Reader> reader, Pc2Reader::Open(pc2_path));
  const Pc2Header& header = reader->header();
  if (static_cast<std::size_t>(header.num_points) != mesh.vertex_count()) {
    return CorruptError(pc2_path + " has " + std::to_string(header.num_points) +
                        " points per frame but " + obj_path + " has " +
                        std::to_string(mesh.vertex_count()) +
                        " vertices; they must be the same animation");
  }
  if (header.num_samples <= 0) {
    return CorruptError(pc2_path + " holds no frame");
  }
  return std::unique_ptr<MeshSequence>(std::make_unique<Pc2MeshSequence>(
      obj_path, pc2_path, std::move(mesh), std::move(reader), frame_rate));
}

StatusOr<std::unique_ptr<MeshSequence>> OpenPatternSequence(const std::string& spec,
                                                            double frame_rate) {
  MESHVID_ASSIGN_OR_RETURN(FilePattern pattern, FilePattern::Parse(spec));
  if (!pattern.has_frame() || pattern.has_view()) {
    return InvalidArgumentError("mesh sequence pattern '" + spec +
                                "' must have a {frame} placeholder and no {view}");
  }
  MESHVID_ASSIGN_OR_RETURN(auto files, pattern.Scan());
  if (files.empty()) return NotFoundError("no file matches the pattern '" + spec + "'");
  std::vector<std::string> paths;
  int expected = files.begin()->first.first;
  for (const auto& [key, path] : files) {
    if (key.first != expected) {
      return NotFoundError("pattern '" + spec + "': frames must be contiguous, but frame " +
                           std::to_string(expected) + " (" + pattern.Expand(expected) +
                           ") is missing before frame " + std::to_string(key.first));
    }
    paths.push_back(path);
    ++expected;
  }
  return std::unique_ptr<MeshSequence>(std::make_unique<FileListMeshSequence>(
      spec + " (" + std::to_string(paths.size()) + " frames)", std::move(paths), frame_rate));
}

StatusOr<std::unique_ptr<MeshSequence>> OpenDirectorySequence(const std::string& spec,
                                                              double frame_rate) {
  std::vector<std::string> paths;
  std::error_code error;
  for (fs::directory_iterator it(spec, error), end; !error && it != end; it.increment(error)) {
    if (it->is_regular_file(error) && IsMeshFile(it->path())) {
      paths.push_back(it->path().string());
    }
  }
  if (error) return IoError(spec + ": cannot list folder: " + error.message());
  if (paths.empty()) return NotFoundError(spec + ": folder holds no .obj or .ply file");
  std::sort(paths.begin(), paths.end());
  return std::unique_ptr<MeshSequence>(std::make_unique<FileListMeshSequence>(
      spec + " (" + std::to_string(paths.size()) + " frames)", std::move(paths), frame_rate));
}

}  // namespace

StatusOr<std::unique_ptr<MeshSequence>> OpenMeshSequence(const std::string& spec,
                                                         double frame_rate) {
  if (FilePattern::LooksLikePattern(spec)) return OpenPatternSequence(spec, frame_rate);
  std::error_code error;
  const fs::path path(spec);
  if (fs::is_directory(path, error)) return OpenDirectorySequence(spec, frame_rate);
  const std::string extension = LowerExtension(path);
  if (extension == ".pc2") {
    const std::string obj = fs::path(path).replace_extension(".obj").string();
    if (!fs::exists(obj, error)) {
      return NotFoundError(spec + ": the template mesh " + obj + " is missing");
    }
    return OpenPc2Sequence(obj, spec, frame_rate);
  }
  if (!fs::exists(path, error)) {
    return NotFoundError(spec +
                         ": no such file or folder (expected NAME.obj with NAME.pc2, a "
                         "folder of .obj/.ply files, a {frame} pattern or a mesh file)");
  }
  if (!IsMeshFile(path)) {
    return UnsupportedError(spec +
                            ": not a mesh sequence (expected NAME.obj with NAME.pc2, a "
                            "folder of .obj/.ply files, a {frame} pattern or a mesh file)");
  }
  const std::string pc2 = fs::path(path).replace_extension(".pc2").string();
  if (extension == ".obj" && fs::exists(pc2, error)) {
    return OpenPc2Sequence(spec, pc2, frame_rate);
  }
  return std::unique_ptr<MeshSequence>(
      std::make_unique<FileListMeshSequence>(spec, std::vector<std::string>{spec}, frame_rate));
}

}  // namespace meshvid
