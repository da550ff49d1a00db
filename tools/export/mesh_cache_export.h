// OBJ + PC2 export: the decoded surface as mesh caches Blender's Mesh Cache modifier (and
// other tools reading Point Cache 2) play, one OBJ + PC2 pair per key group, since each key
// group has its own connectivity.
#ifndef MESHVID_TOOLS_EXPORT_MESH_CACHE_EXPORT_H_
#define MESHVID_TOOLS_EXPORT_MESH_CACHE_EXPORT_H_

#include <string>
#include <vector>

#include "codec/common/progress.h"
#include "codec/dec/mvid_decoder.h"
#include "format/status.h"
#include "tools/export/export_range.h"

namespace meshvid {

/// One OBJ + PC2 pair written.
struct MeshCacheFiles {
  std::string obj;  ///< the key group's triangles, posed as its first exported frame
  std::string pc2;  ///< every exported frame's positions (startFrame: the first's number)
  std::uint32_t key_group = 0;
  std::uint32_t first_frame = 0;
  std::uint32_t frame_count = 0;
};

/// The OBJ path of a run: `obj_path` itself when one key group is exported (so NAME.obj +
/// NAME.pc2 reads back as ground truth), else NAME_kgK.obj.
std::string MeshCacheObjPath(const std::string& obj_path, std::uint32_t key_group,
                             bool several);

/// Decodes the frames of `options` and writes one OBJ + PC2 pair per key group they touch.
StatusOr<std::vector<MeshCacheFiles>> ExportMeshCache(MvidDecoder& decoder,
                                                      const std::string& obj_path,
                                                      const ExportOptions& options,
                                                      const ProgressCallback& progress = {});

}  // namespace meshvid

#endif  // MESHVID_TOOLS_EXPORT_MESH_CACHE_EXPORT_H_
