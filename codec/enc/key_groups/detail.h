// Surface detail (docs/encoder-method.md section 4): per frame, the posed and subdivided base mesh
// shoots its interpolated normals into every view's full-resolution mesh; the hits of all views are
// fused into one displacement per sample, and hole filling makes every frame complete.
#ifndef MESHVID_CODEC_ENC_KEY_GROUPS_DETAIL_H_
#define MESHVID_CODEC_ENC_KEY_GROUPS_DETAIL_H_

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/camera.h"
#include "codec/common/mesh.h"
#include "codec/common/subdivision.h"
#include "codec/enc/key_groups/colour.h"
#include "codec/enc/tracking/normal_shooting.h"
#include "format/status.h"

namespace meshvid {

/// Settings of the displacement measurement.
struct DetailOptions {
  ShotLimits shot;               ///< search along each sample's normal
  float outlier_distance = 0.01f;  ///< hits this far from the views' median are dropped
};

/// Measures the displacement of every sample of `subdivision` (all levels) at one frame:
/// `positions` are the posed base vertices (a decoder's: decoded base, de-quantised
/// transforms), `views` the frame's range meshes. Writes one value per sample into
/// `displacements`, kNoHit where no view saw the surface. Returns the number of hits.
///
/// With `colours`, also records what each view's colour is where its shot hit, for the views
/// with vertex colours and the hits the displacement kept (within the outlier distance),
/// weighted by ViewingWeight of the angle at which the view sees the hit: from its camera
/// centre when `cameras` gives one (cameras[v] with extrinsics), else along the shot.
StatusOr<std::size_t> MeasureDisplacements(const RegularSubdivision& subdivision,
                                           std::span<const Eigen::Vector3f> positions,
                                           std::span<const TriangleMesh> views,
                                           const DetailOptions& options,
                                           std::vector<float>* displacements,
                                           std::span<const ViewCalibration> cameras = {},
                                           ColourObservations* colours = nullptr);

/// The neighbour graph of the finest lattice (compressed rows), for spatial hole filling.
struct SampleGraph {
  std::vector<std::uint32_t> offsets;    ///< size samples + 1
  std::vector<std::uint32_t> neighbours;
  static SampleGraph Build(const RegularSubdivision& subdivision);
};

/// What FillDisplacementGroup gives a sample that no measurement of its frame reaches through
/// the lattice (a part of the base that no view saw in the whole group).
struct UnreachedFill {
  /// Spread from every valued sample, ring by ring, to every sample it reaches. The
  /// displacements keep the seeding their files were made with (false): a sample beyond the
  /// valued samples' first ring may take 0, the base surface, instead of a spread value;
  /// changing it changes every file the encoder writes.
  bool spread_everywhere = false;
  /// Take the mean of the frame's values before the spread (for colour: the subject's
  /// average colour rather than black), else `no_values`.
  bool frame_mean = false;
  /// The value where the frame has none to take (0: no displacement).
  float no_values = 0;
};

/// Fills the misses (kNoHit) of a group of consecutive frames (docs/encoder-method.md section 4): a
/// missing sample takes the average of its nearest measurements before and after it in time
/// (`last_measured` carries each sample's latest measurement across groups) and of its
/// measured lattice neighbours in the same frame; what is still missing is filled by
/// spreading from the filled neighbours, and what that does not reach as `unreached` says.
/// Returns the number of samples filled.
std::size_t FillDisplacementGroup(const SampleGraph& graph, std::vector<float>* last_measured,
                                  std::vector<std::vector<float>>* frames,
                                  const UnreachedFill& unreached = {});

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_KEY_GROUPS_DETAIL_H_
