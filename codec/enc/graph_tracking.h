// Frame-to-frame tracking of a key group's pieces (segments and patches) as one deformation
// graph whose nodes are the pieces (docs/encoder-method.md section 3.3): every piece keeps one
// rigid transform per frame, so the format stores the result as it stores any track. A frame
// is solved jointly from a constant-velocity prediction: a robust point-to-plane data term per
// piece, and neighbouring pieces held to agree on the vertices of the edges between them,
// coarse to fine. A piece that finds little support there is searched for again alone (its
// last pose, its neighbours' motion, closest points over the whole frame within a widening
// radius), and the frame is solved jointly once more.
#ifndef MESHVID_CODEC_ENC_GRAPH_TRACKING_H_
#define MESHVID_CODEC_ENC_GRAPH_TRACKING_H_

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/motion.h"
#include "codec/enc/base_topology.h"
#include "codec/enc/normal_shooting.h"
#include "codec/enc/segmentation.h"

namespace meshvid {

/// A base edge between two different pieces (at least one of them free to move).
struct PieceSeam {
  std::uint32_t u = 0, w = 0;  ///< the edge's vertices
  std::int32_t a = 0, b = 0;   ///< the pieces of u and w
};

/// The pieces of a base as graph nodes: what does not change between frames.
struct PieceGraph {
  int fixed_count = 0;  ///< pieces 0..fixed_count-1 keep their transforms in a joint step
  int piece_count = 0;
  std::vector<std::vector<std::uint32_t>> members;  ///< per piece, its vertices
  std::vector<Eigen::Vector3f> centres;             ///< per piece, its rest centroid
  std::vector<double> radii;                        ///< per piece, its rest RMS radius
  std::vector<PieceSeam> seams;
  std::vector<std::vector<std::int32_t>> adjacent;  ///< per piece, the pieces it meets
};

/// The graph of the pieces `labels` names (labels[v] in 0..piece_count-1; others belong to
/// no piece); pieces below `fixed_count` are held fixed by JointStep.
PieceGraph BuildPieceGraph(const BaseTopology& base, std::span<const std::int32_t> labels,
                           int fixed_count, int piece_count);

/// Splits every piece of more than `node_vertices` members (largest first) into connected
/// nodes of about that many (patch_tracking.h's PartitionUnregistered within the piece): the
/// first keeps the piece's label, the others are appended, while at most `max_pieces` pieces
/// exist. `parents` gets, per piece, the piece it came from (itself for the old ones).
/// Returns the new piece count.
int SplitIntoNodes(const BaseTopology& base, int piece_count, int node_vertices, int max_pieces,
                   std::vector<std::int32_t>* labels, std::vector<std::int32_t>* parents);

/// The terms of one joint Gauss-Newton step.
struct JointStepSettings {
  ShotLimits shot;       ///< the correspondence search (normal shooting)
  float tolerance = 0;   ///< correspondences farther along the normal are left out
  float stiffness = 1;   ///< weight of two pieces agreeing on a seam vertex
  /// Geman-McClure scale of the point-to-plane residuals, as a share of `tolerance`; 0: every
  /// correspondence within the tolerance weighs 1.
  float robust_scale = 0;
  /// Weight of each piece staying where it is, per member and unit of its size: decides
  /// only what neither data nor neighbours do.
  double prior_weight = 0.01;
};

/// One joint Gauss-Newton step of the free pieces' transforms (`transforms[piece]`):
/// point-to-plane data terms of their members' correspondences in `target`, seam agreement,
/// the weak prior. Transforms stay as they were when the system cannot be solved.
void JointStep(const BaseTopology& base, const PieceGraph& graph, const ShootingTarget& target,
               const JointStepSettings& settings, std::vector<RigidTransform>* transforms);

/// Solves the free pieces of one frame coarse to fine from `*transforms`: the tolerance
/// halving from the search distance (seg.shot.max_distance) to seg.initial_tolerance_factor x
/// seg.tolerance, then shrinking by seg.tolerance_shrink to seg.tolerance (from the latter
/// when `fine_only`), seg.icp_iterations joint steps at each.
void SolveJointly(const BaseTopology& base, const PieceGraph& graph, const ShootingTarget& target,
                  const SegmentationOptions& seg, JointStepSettings settings, bool fine_only,
                  std::vector<RigidTransform>* transforms);

/// The constants of the graph tracker (EncoderTuning holds each as an option).
struct GraphTrackingOptions {
  float stiffness = 1;           ///< JointStepSettings::stiffness
  float robust_scale = 0;        ///< JointStepSettings::robust_scale
  double prior_weight = 0.01;    ///< JointStepSettings::prior_weight
  /// A piece with fewer than this share of its members agreeing with the data (within
  /// seg.tolerance) after the joint solve is searched for again.
  float reacquire_below = 0.5f;
  /// A re-acquired pose is kept when this share more of the piece's members agree with it.
  float reacquire_gain = 0.2f;
  int reacquire_min_vertices = 12;   ///< smaller pieces are not searched for alone
  float reacquire_max_distance = 0;  ///< widest closest-point search radius (scene units)
};

/// What the tracking of one frame did.
struct GraphTrackStats {
  int searched = 0;    ///< pieces searched for again
  int reacquired = 0;  ///< of them, pieces moved to a pose their members agree with better
};

/// Tracks the pieces of one key group frame by frame.
class GraphTracker {
 public:
  /// `base` must outlive the tracker; `labels` name each vertex's piece (0..piece_count-1;
  /// others belong to none); pieces below `fixed_count` are not solved (their transforms are
  /// given per frame); `seg` gives the correspondence search and the tolerance schedule.
  GraphTracker(const BaseTopology& base, std::span<const std::int32_t> labels, int piece_count,
               const SegmentationOptions& seg, const GraphTrackingOptions& options,
               int fixed_count = 0);

  /// The pieces' transforms in a frame (`target`: its decimated views; `points`: their
  /// vertices), from the last frame's `previous` and the one before, `before` (empty: none,
  /// the prediction is `previous`); `fixed` holds this frame's transforms of the fixed pieces.
  std::vector<RigidTransform> Track(const ShootingTarget& target,
                                    std::span<const Eigen::Vector3f> points,
                                    std::span<const RigidTransform> previous,
                                    std::span<const RigidTransform> before,
                                    std::span<const RigidTransform> fixed = {},
                                    GraphTrackStats* stats = nullptr) const;

  /// How many of a piece's members agree with the data (a hit within seg.tolerance along the
  /// normal) when posed by `transform`.
  int Agreeing(int piece, const ShootingTarget& target, const RigidTransform& transform) const;

  const PieceGraph& graph() const { return graph_; }

 private:
  /// Searches a poorly supported piece again from its last pose, its neighbours' motion and
  /// `aligned` (poses found by closest points); returns whether its pose changed.
  bool Reacquire(int piece, const ShootingTarget& target, std::span<const RigidTransform> previous,
                 std::vector<RigidTransform> aligned, const std::vector<int>& agreeing,
                 std::vector<RigidTransform>* transforms) const;

  const BaseTopology& base_;
  SegmentationOptions seg_;
  GraphTrackingOptions options_;
  PieceGraph graph_;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_GRAPH_TRACKING_H_
