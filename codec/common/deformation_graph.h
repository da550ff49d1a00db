// An embedded deformation graph over a base mesh (spec/mvid-codec.md, MOTN version 3): nodes
// on base vertices, and every vertex blended over its nearest nodes along the mesh's edges.
// The blend weights follow from the base mesh, the nodes and their spacing alone, so a file
// stores the nodes and a decoder derives the weights exactly as the encoder did.
#ifndef MESHVID_CODEC_COMMON_DEFORMATION_GRAPH_H_
#define MESHVID_CODEC_COMMON_DEFORMATION_GRAPH_H_

#include <cstdint>
#include <span>
#include <vector>

#include "codec/common/mesh.h"
#include "codec/common/motion.h"
#include "format/status.h"

namespace meshvid {

/// A node reaches vertices up to this many spacings away along the edges.
inline constexpr float kNodeReachSpacings = 3.0f;

/// A blend weight derived from a graph is a multiple of 1 / kNodeWeightSteps.
inline constexpr int kNodeWeightSteps = 32;

/// Nodes about `spacing` apart along the edges of `mesh` (`neighbours`: its one-rings): in
/// vertex order, a node on every vertex no earlier node reaches within `spacing`. Every
/// connected piece of the mesh gets a node. `spacing` must be positive and finite.
std::vector<std::uint32_t> SampleDeformationNodes(
    const TriangleMesh& mesh, const std::vector<std::vector<std::uint32_t>>& neighbours,
    float spacing);

/// The blends of `mesh`'s vertices over the nodes on `node_vertices` (node i on vertex
/// node_vertices[i]), as spec/mvid-codec.md states them: each vertex's at most kMaxInfluences
/// nearest nodes within kNodeReachSpacings x `spacing` along the edges, Gaussian weights of
/// width `spacing` rounded to multiples of 1 / kNodeWeightSteps. Fails (as corrupt data) on
/// a node index out of range or repeated, a spacing that is not positive and finite, a vertex
/// no node reaches, or nodes so dense for their spacing that the search would not be bounded.
StatusOr<std::vector<VertexBlend>> DeriveNodeBlends(
    const TriangleMesh& mesh, const std::vector<std::vector<std::uint32_t>>& neighbours,
    std::span<const std::uint32_t> node_vertices, float spacing);

/// The motion model of nodes sampled over `mesh` `spacing` apart (SampleDeformationNodes), with
/// every vertex's blend derived from them (DeriveNodeBlends): what MOTN version 3 stores.
StatusOr<MotionModel> SampleNodeMotion(const TriangleMesh& mesh,
                                       const std::vector<std::vector<std::uint32_t>>& neighbours,
                                       float spacing);

/// Fills `model`'s blends from its nodes (MotionModel::node_vertices) and `mesh`.
Status CompleteNodeBlends(const TriangleMesh& mesh, MotionModel* model);

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_DEFORMATION_GRAPH_H_
