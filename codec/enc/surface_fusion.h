// Fusion of several range meshes of one instant (the views of one frame, in world
// coordinates) into one surface: the automatic base mesh's first step (method.md "Base mesh"),
// and the per-frame baseline of `meshvid bench`.
#ifndef MESHVID_CODEC_ENC_SURFACE_FUSION_H_
#define MESHVID_CODEC_ENC_SURFACE_FUSION_H_

#include <span>

#include "codec/common/mesh.h"
#include "codec/common/progress.h"
#include "format/status.h"

namespace meshvid {

/// Settings of the view fusion.
struct SurfaceFusionOptions {
  /// Sample spacing of the output surface in scene units; 0: derived from the data (its
  /// average point spacing).
  double spacing = 0;
  /// Most input points used; denser input is thinned on a grid first (speed bound).
  std::size_t max_points = 60000;
};

/// Fuses range meshes into one closed surface (watertight where the data allows), oriented
/// with normals pointing out of the captured object. Views may overlap, be noisy and have
/// holes. Fails if the views hold too few points to reconstruct anything.
StatusOr<TriangleMesh> FuseRangeMeshes(std::span<const TriangleMesh> views,
                                       const SurfaceFusionOptions& options = {},
                                       const ProgressCallback& progress = {});

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_SURFACE_FUSION_H_
