// The multi-frame piecewise-rigid segmentation of docs/encoder-method.md section 3: base vertices
// are grouped into segments, each following one rigid transform per frame, found jointly over the
// frames (eq. 5) on the vertices whose correspondences agree within a tolerance (eq. 6).
#ifndef MESHVID_CODEC_ENC_SEGMENTATION_H_
#define MESHVID_CODEC_ENC_SEGMENTATION_H_

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"
#include "codec/common/motion.h"
#include "codec/common/progress.h"
#include "codec/enc/base_topology.h"
#include "codec/enc/normal_shooting.h"
#include "format/status.h"

namespace meshvid {

/// The constants of the segmentation (every one an encoder option).
struct SegmentationOptions {
  float tolerance = 0.01f;              ///< UserTol of eq. 6, scene units
  float initial_tolerance_factor = 3;   ///< each window starts at this x tolerance
  float tolerance_shrink = 0.8f;        ///< per step, until the tolerance is reached
  int min_segment_vertices = 3;         ///< eq. 5 needs at least 3 points
  /// Vertices of the patch around a seed vertex that a new segment is first tracked with
  /// (then grown); 0: a fortieth of the base, at least 3 x min_segment_vertices.
  int seed_vertices = 0;
  int max_segments = 64;
  int occlusion_frames = 5;             ///< frames a member may fail eq. 6 (t_occ)
  int icp_iterations = 3;               ///< correspondence + solve rounds per step
  float max_turn_per_frame = 0.349f;    ///< radians (20 degrees) a segment may turn per frame
  /// A segment must be solved (enough of its members agree) in at least this share of the
  /// frames after the first, or it is dropped as lost.
  float min_solved_share = 0.75f;
  ShotLimits shot;                      ///< correspondence search (docs/encoder-method.md eq. 4)
};

/// Correspondence targets: one per frame (the decimated views of that frame, appended).
using FrameTargets = std::span<const ShootingTarget* const>;

/// Marks a vertex that joined no segment.
inline constexpr std::int32_t kUnregistered = -1;

/// A segmentation and the segments' transforms over the frames it looked at.
struct Segmentation {
  std::vector<std::int32_t> labels;  ///< per base vertex: segment or kUnregistered
  int segment_count = 0;
  /// transforms[frame][segment], frame = index into the targets it was computed on.
  std::vector<std::vector<RigidTransform>> transforms;
};

/// Segments `base` (posed as in frame 0 of `targets`, i.e. fitted to it) over every frame of
/// `targets` (null entries are frames without data). Each segment starts as a patch around a
/// seed vertex (the middle of the largest region still free and seen in the first frame with
/// data), is tracked through the frames, then grows over every unsegmented vertex that
/// follows its track. Reports progress per segment attempt. No segment at all (segment_count
/// 0, every vertex kUnregistered) means no connected region of the base, min_segment_vertices
/// large, lies within the tolerance of the data through the frames: the caller decides.
StatusOr<Segmentation> SegmentPiecewiseRigid(const BaseTopology& base, FrameTargets targets,
                                             const SegmentationOptions& options,
                                             const ProgressCallback& progress = {});

/// Tracks fixed segments through one more frame: starting from `initial[segment]`, solves each
/// segment's transform on its members' correspondences in `target` (a fine and a coarse
/// search). A segment whose solve is not believable (too few members agree, or it jumped or
/// turned too far) keeps its initial transform.
std::vector<RigidTransform> TrackSegments(const BaseTopology& base,
                                          std::span<const std::int32_t> labels,
                                          int segment_count, const ShootingTarget& target,
                                          std::span<const RigidTransform> initial,
                                          const SegmentationOptions& options);

/// Solves one piece's transform in one frame from `*transform` alone, as TrackSegments does
/// for each segment (a fine and a coarse search; believable relative to the start pose).
/// Returns how many members agree within options.tolerance, or -1 (leaving `*transform` as
/// it was) when neither search is believable.
int SolveSegment(const BaseTopology& base, std::span<const std::uint32_t> members,
                 const ShootingTarget& target, const SegmentationOptions& options,
                 RigidTransform* transform);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_SEGMENTATION_H_
