// glTF 2.0 binary (.glb) export of a .mvid's coarse motion, for Blender, three.js and game
// engines: per key group its base mesh with a skin (one joint per segment, the blend weights as
// joint weights, at most 4 per vertex) and the segments' per-frame transforms as an animation.
// Each key group's joints hang under one node whose scale is 1 during the key group's frames
// and 0 otherwise (STEP), so only the key group in use is seen. Displacements are not exported.
#ifndef MESHVID_TOOLS_EXPORT_GLTF_EXPORT_H_
#define MESHVID_TOOLS_EXPORT_GLTF_EXPORT_H_

#include <cstdint>
#include <string>

#include "codec/common/progress.h"
#include "codec/dec/mvid_decoder.h"
#include "format/status.h"
#include "tools/export/export_range.h"

namespace meshvid {

/// What an export holds.
struct GltfExportStats {
  std::uint32_t key_groups = 0;
  std::uint32_t joints = 0;  ///< over every key group
  std::uint32_t frames = 0;
  std::size_t bytes = 0;     ///< of the .glb
};

/// The .glb bytes of the frames of `options` (its level is not used: base meshes only). The
/// animation starts at time 0 with the first frame, one frame every 1/frame rate seconds.
StatusOr<std::string> EncodeGltf(MvidDecoder& decoder, const ExportOptions& options,
                                 const ProgressCallback& progress = {},
                                 GltfExportStats* stats = nullptr);

/// EncodeGltf() written to `path` (parent folders created, written atomically).
StatusOr<GltfExportStats> ExportGltf(MvidDecoder& decoder, const std::string& path,
                                     const ExportOptions& options,
                                     const ProgressCallback& progress = {});

}  // namespace meshvid

#endif  // MESHVID_TOOLS_EXPORT_GLTF_EXPORT_H_
