#include "tools/export/mesh_cache_export.h"

#include <memory>

#include "format/output_file.h"
#include "tools/io/mesh_io.h"
#include "tools/io/pc2.h"

namespace meshvid {
namespace {

/// `path` without its extension (".obj"), if it has one.
std::string Stem(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return path;
  return path.substr(0, dot);
}

Status WriteObjFile(const std::string& path, const TriangleMesh& mesh) {
  MESHVID_ASSIGN_OR_RETURN(std::unique_ptr<OutputFile> out, OutputFile::Open(path));
  MeshWriteOptions options;
  options.write_normals = false;
  MESHVID_RETURN_IF_ERROR(WriteObj(out->stream(), mesh, options).WithContext(path));
  return out->Commit();
}

}  // namespace

std::string MeshCacheObjPath(const std::string& obj_path, std::uint32_t key_group,
                             bool several) {
  if (!several) return obj_path;
  return Stem(obj_path) + "_kg" + std::to_string(key_group) + ".obj";
}

StatusOr<std::vector<MeshCacheFiles>> ExportMeshCache(MvidDecoder& decoder,
                                                      const std::string& obj_path,
                                                      const ExportOptions& options,
                                                      const ProgressCallback& progress) {
  MESHVID_ASSIGN_OR_RETURN(const ExportOptions resolved,
                           ResolveExportOptions(decoder.info(), options));
  MESHVID_ASSIGN_OR_RETURN(const std::vector<KeyGroupRun> runs,
                           KeyGroupRuns(decoder, resolved));
  const long total = static_cast<long>(resolved.end_frame - resolved.first_frame);
  std::vector<MeshCacheFiles> written;
  for (const KeyGroupRun& run : runs) {
    MeshCacheFiles files;
    files.obj = MeshCacheObjPath(obj_path, run.key_group, runs.size() > 1);
    files.pc2 = Stem(files.obj) + ".pc2";
    files.key_group = run.key_group;
    files.first_frame = run.first;
    files.frame_count = run.end - run.first;
    std::unique_ptr<Pc2Writer> pc2;
    for (std::uint32_t frame = run.first; frame < run.end; ++frame) {
      MESHVID_ASSIGN_OR_RETURN(TriangleMesh mesh, decoder.DecodeFrame(frame, resolved.level));
      if (frame == run.first) {
        MESHVID_RETURN_IF_ERROR(WriteObjFile(files.obj, mesh));
        MESHVID_ASSIGN_OR_RETURN(
            pc2, Pc2Writer::Create(files.pc2, static_cast<std::int32_t>(mesh.vertex_count()),
                                   static_cast<float>(run.first), 1.0f));
      }
      MESHVID_RETURN_IF_ERROR(pc2->AppendFrame(mesh.positions));
      if (!ReportProgress(progress, "exporting", frame - resolved.first_frame + 1, total)) {
        return CancelledError("export cancelled");
      }
    }
    MESHVID_RETURN_IF_ERROR(pc2->Finish());
    written.push_back(files);
  }
  return written;
}

}  // namespace meshvid
