// What the analysis derives once from a key group's base mesh and every stage shares: its
// vertex one-rings and unposed normals.
#ifndef MESHVID_CODEC_ENC_TRACKING_BASE_TOPOLOGY_H_
#define MESHVID_CODEC_ENC_TRACKING_BASE_TOPOLOGY_H_

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"

namespace meshvid {

/// A base mesh with its one-rings and vertex normals, computed once. Holds a reference to the
/// mesh, which must outlive it. Converts from a TriangleMesh where a stage is called alone.
struct BaseTopology {
  BaseTopology(const TriangleMesh& base)  // NOLINT(google-explicit-constructor)
      : mesh(base), neighbours(VertexNeighbours(base)), normals(ComputeVertexNormals(base)) {}
  const TriangleMesh& mesh;
  std::vector<std::vector<std::uint32_t>> neighbours;  ///< per vertex, its mesh neighbours
  std::vector<Eigen::Vector3f> normals;                ///< per vertex, unposed
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_TRACKING_BASE_TOPOLOGY_H_
