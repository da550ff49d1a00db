// The key-group rule and the figures both of a key group's trackers share (internal to the
// encoder): whether a fresh base is worth its bytes at a tracked frame (FitMeter,
// TrackedFrameExplained), what ended a key group, which base triangles some view
// saw, and a frame's views fused as a key frame's base is.
#ifndef MESHVID_CODEC_ENC_KEY_GROUPS_KEY_GROUP_RULES_H_
#define MESHVID_CODEC_ENC_KEY_GROUPS_KEY_GROUP_RULES_H_

#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"
#include "codec/common/motion.h"
#include "codec/common/subdivision.h"
#include "codec/enc/key_groups/key_group_analysis.h"
#include "codec/enc/tracking/data_fit.h"
#include "codec/enc/tracking/normal_shooting.h"
#include "format/status.h"

namespace meshvid {

/// Whether a tracked frame stays in its key group: a fresh base would not gain the D1 its
/// bytes are worth at the quality (StillExplains with RebaseGainDb, the farthest growth, and
/// the surface a fresh base would lose, `forgotten`, within rebase_forgotten_excuse_db).
bool TrackedFrameExplained(const EncodeContext& ctx, const DataFit& key_fit, const DataFit& fit,
                           const ForgottenSurface& forgotten = {});

/// TrackedFrameExplained, with its figures recorded in `summary`: for a frame that stays,
/// the key group's worst unexplained share and estimated loss (TrackingLossDb) so far; for
/// one that does not, what ended the key group (the cut_* figures, against `key_fit`).
bool KeepTrackedFrame(const EncodeContext& ctx, const DataFit& key_fit, const DataFit& fit,
                      const ForgottenSurface& forgotten, KeyGroupSummary* summary);

/// For a key group that may not be cut (max_key_groups): records frame `frame` in
/// summary->held_frames where KeepTrackedFrame would have ended the key group, and the key
/// group's worst figures either way.
void RecordHeldFrame(const EncodeContext& ctx, const DataFit& key_fit, const DataFit& fit,
                     const ForgottenSurface& forgotten, int frame, KeyGroupSummary* summary);

/// The surface a fresh base fused from a frame would lose (ForgottenSurface): the base
/// vertices `observed` at earlier frames of the key group, posed by `track`, that lie beyond
/// the displacement range of `frame_surface` (the frame's fused surface, as points) where
/// `free_space` does not say a camera saw through them; distances capped at
/// rebase_forgotten_reach displacement ranges. Empty when that knob is 0 or without cameras
/// (`free_space` null): then nothing tells surface the views lost from surface the subject
/// left.
ForgottenSurface MeasureForgottenSurface(const EncodeContext& ctx, const TriangleMesh& base,
                                         const MotionModel& motion,
                                         std::span<const RigidTransform> track,
                                         const std::vector<char>& observed,
                                         std::span<const Eigen::Vector3f> frame_surface,
                                         const SeenFreeSpace* free_space);

/// Clears them (-1): no frame has ended the key group.
void ClearCut(KeyGroupSummary* summary);

/// How much of a frame a tracked pose fails to explain, as the key-group rule sees it: the
/// share of the data beyond the displacement range plus the share of the surface lying where
/// a camera saw through.
inline double DataMiss(const DataFit& fit) {
  return fit.unexplained_share + fit.seen_through_share;
}

/// A frame's views fused into one closed surface (at most `fusion_points` of their points).
StatusOr<TriangleMesh> FuseFrame(const EncodeContext& ctx, const std::vector<TriangleMesh>& views,
                                 std::size_t fusion_points);

/// Marks the base vertices some view sees in one frame (`target`) when posed by `track`:
/// a shot along the posed normal hits within the displacement range.
void ObserveVertices(const EncodeContext& ctx, const TriangleMesh& base,
                     const MotionModel& motion, const ShootingTarget& target,
                     std::span<const RigidTransform> track, std::vector<char>* observed);

/// The base triangles some view saw (two corners or more, `observed`); sets the summary's
/// share and, with hide_unseen, the motion's surface mask.
void MarkSurface(const EncodeContext& ctx, const TriangleMesh& base,
                 const std::vector<char>& observed, MotionModel* motion,
                 KeyGroupSummary* summary);

/// Measures how well the base posed by `transforms` explains a frame's data points.
class FitMeter {
 public:
  /// `judge_across`: SeenFreeSpace::Judge's `across_too`, as each tracker's key-group
  /// threshold was measured.
  FitMeter(const TriangleMesh& base, const MotionModel& motion, const RegularSubdivision& lattice,
           float representable_distance, float stray_distance, bool judge_across)
      : base_(base),
        motion_(motion),
        lattice_(lattice),
        distance_(representable_distance),
        stray_distance_(stray_distance),
        judge_across_(judge_across),
        triangles_(lattice.Triangles(lattice.levels())) {}
  /// The fit of `frame`'s data to the base posed by `transforms` (one per piece or node).
  DataFit Measure(const std::vector<RigidTransform>& transforms, const FrameProxy& frame);

 private:
  const TriangleMesh& base_;
  const MotionModel& motion_;
  const RegularSubdivision& lattice_;
  float distance_, stray_distance_;
  bool judge_across_;
  std::vector<Triangle> triangles_;  ///< the lattice's finest triangles
  std::vector<Eigen::Vector3f> posed_, normals_, samples_, directions_;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_KEY_GROUPS_KEY_GROUP_RULES_H_
