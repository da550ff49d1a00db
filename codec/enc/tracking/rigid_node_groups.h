// Rigid groups of a deformation graph's nodes: after a key group is tracked node by node
// (deformation_tracking.h), the nodes that moved as one rigid body through all its frames
// (a block, a forearm) are joined into a group and given one rigid transform per frame, fitted
// to the group's vertices. The file keeps one track per node, so a decoder is unchanged; the
// group's nodes simply carry the same transforms, and the part is then posed exactly rigidly
// (as editing, skinning and texture reuse want) instead of bending with the tracker's noise.
#ifndef MESHVID_CODEC_ENC_TRACKING_RIGID_NODE_GROUPS_H_
#define MESHVID_CODEC_ENC_TRACKING_RIGID_NODE_GROUPS_H_

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/motion.h"

namespace meshvid {

/// Which group each node joined.
struct RigidNodeGroups {
  std::vector<std::int32_t> group_of_node;  ///< per node, its group in [0, group_count)
  int group_count = 0;
  /// Per frame of the tracks the groups were found in, per group, the rigid transform that
  /// best maps the vertices its nodes move, at rest, onto where each node's own transform puts
  /// them (least squares, weighted by the influences); identity for a group of one node.
  std::vector<std::vector<RigidTransform>> transforms;
};

/// Joins neighbouring nodes (`adjacent`, per node) greedily, the pair that stays most rigid
/// first, while in every frame one rigid transform, fitted to the group, stays within
/// `tolerance` of each node's own transform in `tracks` (per frame, per node) on the vertices
/// the node moves (RMS, weighted by its influence on them). `rest` are the base's vertex
/// positions and `motion` their blends over the nodes.
RigidNodeGroups FindRigidNodeGroups(std::span<const Eigen::Vector3f> rest,
                                    const MotionModel& motion,
                                    std::span<const std::vector<std::int32_t>> adjacent,
                                    std::span<const std::vector<RigidTransform>> tracks,
                                    float tolerance);

/// Gives every node of a group of more than one node the group's transform in each frame of
/// `tracks`, the tracks `groups` were found in.
void ApplyRigidNodeGroups(const RigidNodeGroups& groups,
                          std::vector<std::vector<RigidTransform>>* tracks);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_TRACKING_RIGID_NODE_GROUPS_H_
