// Motion for the vertices the segmentation left unregistered (docs/encoder-method.md section 3.1):
// they are split into small patches, each a further segment with its own rigid track, and the
// patches of a frame are solved jointly: each on its own correspondences, all held together where
// they meet each other or a segment (as an embedded deformation graph is). A patch the views do not
// see in a frame moves with its neighbours. The paper interpolates these vertices' transforms from
// the segments around them, which fails where most of the surface is unregistered (a dancer whose
// limbs leave the views).
#ifndef MESHVID_CODEC_ENC_PATCH_TRACKING_H_
#define MESHVID_CODEC_ENC_PATCH_TRACKING_H_

#include <cstdint>
#include <vector>

#include "codec/common/mesh.h"
#include "codec/common/motion.h"
#include "codec/common/progress.h"
#include "codec/enc/segmentation.h"
#include "format/status.h"

namespace meshvid {

/// The constants of the patch tracking.
struct PatchTrackingOptions {
  int patch_vertices = 40;  ///< vertices per patch (the last patches of a region may differ)
  int max_segments = 64;    ///< segments and patches together
  /// Weight of the agreement of two neighbouring pieces at their common vertices, against
  /// a point's distance to the data.
  float stiffness = 1.0f;
};

/// Splits the unregistered vertices (labels[v] < 0) into patches of about
/// options.patch_vertices connected vertices, labelled segment_count, segment_count + 1, ...
/// (nearest patch seed along the mesh's edges). Regions smaller than
/// `min_patch_vertices` stay unregistered; at most options.max_segments - segment_count
/// patches are made (regions get patches in proportion to their size). Returns the new
/// segment count.
int PartitionUnregistered(const BaseTopology& base, int segment_count, int min_patch_vertices,
                          const PatchTrackingOptions& options, std::vector<std::int32_t>* labels);

/// Tracks patches fixed_count..total_count-1 of `labels` through `targets` (one per frame,
/// null: no data; frame 0 is where the base is fitted, so patches start at the identity).
/// `transforms[frame]` holds the fixed segments' transforms (kept as they are) and gets the
/// patches' appended. Each frame starts from a constant-velocity prediction and alternates
/// correspondences (normal shooting, the tolerance shrinking from the search distance to
/// seg.tolerance) with one joint Gauss-Newton step of all patches.
Status TrackPatches(const BaseTopology& base, const std::vector<std::int32_t>& labels,
                    int fixed_count, int total_count, FrameTargets targets,
                    const SegmentationOptions& seg, const PatchTrackingOptions& options,
                    std::vector<std::vector<RigidTransform>>* transforms,
                    const ProgressCallback& progress = {});

/// Patches that moved with a neighbouring segment join it: a patch adjacent to segment s
/// (s < fixed_count) whose members both tracks put within seg.tolerance (RMS) of each other
/// in all but seg.occlusion_frames frames is relabelled s. The remaining patches are
/// renumbered from fixed_count and `transforms` shrinks to match. Returns the new count.
int MergePatchesIntoSegments(const BaseTopology& base, int fixed_count, int total_count,
                             const SegmentationOptions& seg, std::vector<std::int32_t>* labels,
                             std::vector<std::vector<RigidTransform>>* transforms);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_PATCH_TRACKING_H_
