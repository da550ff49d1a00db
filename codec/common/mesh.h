// TriangleMesh: the one in-memory mesh type of meshvid, shared by I/O, simulator, evaluation,
// encoder and decoder.
#ifndef MESHVID_CODEC_COMMON_MESH_H_
#define MESHVID_CODEC_COMMON_MESH_H_

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "format/status.h"

namespace meshvid {

/// Three vertex indices, counter-clockwise seen from the outside.
using Triangle = Eigen::Matrix<std::uint32_t, 3, 1>;

/// A vertex's colour: red, green and blue, 8 bits each (sRGB, as capture files store it).
using Colour = Eigen::Matrix<std::uint8_t, 3, 1>;

/// An indexed triangle mesh in single precision. `normals` is optional: empty, or one unit
/// normal per position.
struct TriangleMesh {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Triangle> triangles;
  std::vector<Eigen::Vector3f> normals;
  /// Per-vertex colours, as the capture's files give them: empty, or one per vertex.
  std::vector<Colour> colours;

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
  bool empty() const { return positions.empty() || triangles.empty(); }
};

/// Checks what every consumer of a mesh relies on: at least one triangle, every coordinate
/// finite, every index in range, normals absent or one finite normal per vertex, colours absent
/// or one per vertex. `what` names the mesh in
/// the message (usually its file).
Status ValidateMesh(const TriangleMesh& mesh, std::string_view what);

/// Axis-aligned bounding box of the positions (empty box for an empty mesh).
Eigen::AlignedBox3f BoundingBox(const TriangleMesh& mesh);

/// The colour at a point of triangle `t` with barycentric weights (1 - u - v, u, v) of its
/// corners: the corners' colours (`colours`, one per vertex) blended, 0..255 per channel.
inline Eigen::Vector3f BlendColours(std::span<const Colour> colours, const Triangle& t, float u,
                                    float v) {
  return (1.0f - u - v) * colours[t[0]].cast<float>() + u * colours[t[1]].cast<float>() +
         v * colours[t[2]].cast<float>();
}

/// True if a frame's views carry colour: every view with vertices has a colour per vertex,
/// and at least one view has colours.
bool ViewsHaveColour(std::span<const TriangleMesh> views);

/// Appends `src` to `dst`, offsetting its indices. Normals and colours are each kept only if
/// both have them.
void AppendMesh(const TriangleMesh& src, TriangleMesh* dst);

/// The one-ring of each vertex of `mesh`, sorted, without duplicates.
std::vector<std::vector<std::uint32_t>> VertexNeighbours(const TriangleMesh& mesh);

/// Area-weighted unit vertex normals (zero vector for an isolated vertex).
std::vector<Eigen::Vector3f> ComputeVertexNormals(const TriangleMesh& mesh);
/// The same for positions and triangles held apart (e.g. a posed copy of a mesh's vertices),
/// written into `normals` (resized to the vertex count) so a caller can reuse the buffer.
void ComputeVertexNormals(std::span<const Eigen::Vector3f> positions,
                          std::span<const Triangle> triangles,
                          std::vector<Eigen::Vector3f>* normals);

/// Unit normal of triangle `t` (zero for a degenerate triangle).
Eigen::Vector3f TriangleNormal(const TriangleMesh& mesh, std::size_t t);

/// Total surface area.
double SurfaceArea(const TriangleMesh& mesh);

/// Applies a rigid or affine transform to positions (and rotates normals).
void TransformMesh(const Eigen::Affine3d& transform, TriangleMesh* mesh);

/// Removes vertices no triangle references, renumbering the triangles.
void RemoveUnreferencedVertices(TriangleMesh* mesh);

/// Gives each fan of triangles around a vertex its own vertex: where two or more fans touch
/// at one vertex only (a contour's sheets meeting at a grid point), all but the first get a
/// copy of it, appended (normals and colours copied too). Edges are left as they are. Mesh
/// coders (Draco's edgebreaker) split such vertices themselves, which breaks a vertex-indexed
/// mapping. Returns the number of vertices added.
std::size_t SplitNonManifoldVertices(TriangleMesh* mesh);

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_MESH_H_
