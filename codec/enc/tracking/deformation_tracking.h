// Frame-to-frame non-rigid tracking of a key group's base as an embedded deformation (Sumner
// et al. 2007; docs/encoder-method.md section 3): graph nodes sampled over the base surface,
// every vertex blended over its nearest nodes along the surface, every node a rigid transform
// per frame. That is the format's motion model as it stands (a node is a piece, the blend its
// weights), so a decoder poses the result as any other track.
//
// A frame is solved by Gauss-Newton from a constant-velocity prediction of every node: the
// posed base is pulled to the closest of the frame's data points with a compatible normal
// (point-to-plane, and a little point-to-point so that it does not slide along flat data),
// and neighbouring nodes are held to agree on where they put each other as they did in the
// previous frame (as rigid as possible from frame to frame). Coarse to fine: the
// correspondence radius halves from the search distance to two tolerances. A part that
// finds no data near where the solve left it (a limb that moved farther than the search
// distance) is searched for again over the whole frame as one rigid body.
#ifndef MESHVID_CODEC_ENC_TRACKING_DEFORMATION_TRACKING_H_
#define MESHVID_CODEC_ENC_TRACKING_DEFORMATION_TRACKING_H_

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/common/motion.h"
#include "codec/enc/tracking/base_topology.h"
#include "format/status.h"

namespace meshvid {

/// The nodes of a base: what does not change between frames.
struct DeformationGraph {
  std::vector<std::vector<std::int32_t>> adjacent;  ///< per node, the nodes it is held to
  /// The nodes (segment s sits on base vertex motion.node_vertices[s]), their spacing, and the
  /// blend of every base vertex over at most kMaxInfluences of them.
  MotionModel motion;
  std::size_t node_count() const { return motion.node_vertices.size(); }
};

/// Samples nodes over `base` about `node_spacing` apart along its edges and blends every
/// vertex over its nearest nodes (codec/common/deformation_graph.h: the motion model a file
/// stores as nodes), and joins nodes that blend a vertex together or are nearest to the two
/// ends of an edge. With `join_distance` > 0, every node is also joined to the nearest node
/// within that distance of a piece the surface does not connect it to: a fusion leaves a hand
/// apart from the block it holds, and a small piece held to nothing drifts onto whatever data
/// lies near (0: pieces move apart).
StatusOr<DeformationGraph> BuildDeformationGraph(const BaseTopology& base, float node_spacing,
                                                 float join_distance = 0);

/// A frame's data points as the tracker searches them.
struct TrackingData {
  std::span<const Eigen::Vector3f> points;
  std::span<const Eigen::Vector3f> normals;  ///< unit, one per point (zero: no normal)
};

/// The tracker's constants (EncoderTuning holds each as an option).
struct DeformationTrackingOptions {
  float max_distance = 0;       ///< first correspondence radius (scene units)
  float tolerance = 0;          ///< the last radius is 2x this
  float min_normal_cos = 0.5f;  ///< smallest cosine between base and data normals
  /// Weight of neighbouring nodes agreeing on each other's positions, against the data (1: a
  /// node's edges weigh as much as the vertices it carries).
  double rigidity = 0.1;
  /// Weight of the point-to-point distance beside the point-to-plane one.
  double point_weight = 0.1;
  /// On a frame without a velocity to predict from (Track's `before` empty), the rigidity's
  /// multiplier at the first (coarsest) radius, falling geometrically to 1 at the last.
  double coarse_stiffness = 1;
  int iterations = 3;  ///< Gauss-Newton steps per radius
  /// Steps per radius on a frame without a velocity to predict from (Track's `before` empty).
  int first_iterations = 3;
  /// Re-acquisition of lost parts (0: none): after the solve, nodes fewer than
  /// `reacquire_below` of whose nearest vertices have data within the last radius are joined
  /// into connected parts; each part of at least `reacquire_min_vertices` such vertices is
  /// aligned as one rigid body by closest points over the whole frame, within radii widening
  /// from twice max_distance to this distance, and from its pose turned about its joint by 20
  /// and 40 degrees either way about each axis, and moved where at least `reacquire_gain` more
  /// of them (and `reacquire_below` in all) find data. The frame is then solved again at the
  /// two finest radii, and kept when more of the base's vertices find data.
  float reacquire_max_distance = 0;
  float reacquire_below = 0.5f;
  float reacquire_gain = 0.2f;
  int reacquire_min_vertices = 12;
};

/// What one frame's tracking did beyond the solve.
struct DeformationTrackStats {
  int reacquired = 0;  ///< lost parts moved to where their data is
};

/// Tracks the nodes of one key group frame by frame.
class DeformationTracker {
 public:
  /// `base` and `graph` must outlive the tracker.
  DeformationTracker(const BaseTopology& base, const DeformationGraph& graph,
                     const DeformationTrackingOptions& options);

  /// The nodes' transforms in a frame, from the last frame's `previous` and the one before,
  /// `before` (empty: none, the prediction is `previous`).
  std::vector<RigidTransform> Track(const TrackingData& frame,
                                    std::span<const RigidTransform> previous,
                                    std::span<const RigidTransform> before,
                                    DeformationTrackStats* stats = nullptr) const;

 private:
  const BaseTopology& base_;
  const DeformationGraph& graph_;
  DeformationTrackingOptions options_;
  double edge_weight_ = 1;  ///< rigidity weight of one edge per unit of options_.rigidity
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_TRACKING_DEFORMATION_TRACKING_H_
