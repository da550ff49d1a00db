// The coarse motion of a meshvid sequence: a segmentation of the base mesh into rigid pieces,
// per-vertex blend weights over the segments' transforms, and a rigid transform per segment
// per frame. A vertex's posed position is the weighted blend of its segments' transforms
// applied to its base position (docs/encoder-method.md eq. 1: linear blend skinning).
#ifndef MESHVID_CODEC_COMMON_MOTION_H_
#define MESHVID_CODEC_COMMON_MOTION_H_

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// A rigid transform x -> rotation * x + translation.
struct RigidTransform {
  Eigen::Quaternionf rotation = Eigen::Quaternionf::Identity();
  Eigen::Vector3f translation = Eigen::Vector3f::Zero();

  Eigen::Vector3f Apply(const Eigen::Vector3f& x) const { return rotation * x + translation; }
};

/// a after b: x -> a(b(x)).
RigidTransform Compose(const RigidTransform& a, const RigidTransform& b);

/// The transform undoing t.
RigidTransform Inverse(const RigidTransform& t);

/// The next transform of a track moving at constant velocity: the step from `before` to
/// `last`, applied once more after `last`.
RigidTransform PredictConstantVelocity(const RigidTransform& before, const RigidTransform& last);

/// One influence of a segment on a vertex.
struct BlendInfluence {
  std::uint32_t segment = 0;
  float weight = 0;
};

/// Most segments one vertex blends.
inline constexpr int kMaxInfluences = 4;

/// Per-vertex blend weights: up to kMaxInfluences influences, weights summing to 1. A vertex
/// registered to one segment has a single influence of weight 1.
struct VertexBlend {
  std::array<BlendInfluence, kMaxInfluences> influences{};
  std::uint8_t count = 0;
};

/// The static part of the motion: segment count and the blend of every base vertex.
struct MotionModel {
  std::uint32_t segment_count = 0;
  std::vector<VertexBlend> blends;  ///< one per base vertex
  /// Per base triangle: 1 if it is part of the captured surface, 0 if hidden (no view ever
  /// saw it: a decoder leaves out its triangles at every level). Empty: all are surface.
  std::vector<std::uint8_t> surface_triangles;
  /// An embedded deformation graph (MOTN version 3): segment s is a node on base vertex
  /// node_vertices[s], and the blends are derived from the nodes, `node_spacing` and the base
  /// mesh (deformation_graph.h's DeriveNodeBlends) rather than stored. Empty: stored blends.
  std::vector<std::uint32_t> node_vertices;
  float node_spacing = 0;
};

/// MOTN `motion_version` values (spec/mvid-codec.md 2.1-2.3). 1: stored blends, no surface
/// mask; 2: stored blends and `mask_triangle_count` (a model without a mask is written as 1,
/// so the field is not spent on saying "no mask"); 3: a deformation graph's nodes instead of
/// blends, and the mask count.
inline constexpr std::uint8_t kMotionVersionWithoutMask = 1;
inline constexpr std::uint8_t kMotionVersionWithMask = 2;
inline constexpr std::uint8_t kMotionVersionNodes = 3;

/// Checks counts, segment indices, weights in [0, 1] summing to 1 (within 1e-3).
Status ValidateMotionModel(const MotionModel& model, std::size_t vertex_count);

/// Poses base positions with one frame's segment transforms (`transforms[s]` for segment s):
/// each vertex is the weighted sum of its segments' transforms applied to it.
void PoseVertices(const MotionModel& model, std::span<const RigidTransform> transforms,
                  std::span<const Eigen::Vector3f> base_positions,
                  std::vector<Eigen::Vector3f>* posed);

/// A motion model with every vertex in segment 0 (a rigid whole).
MotionModel SingleSegmentModel(std::size_t vertex_count);

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_MOTION_H_
