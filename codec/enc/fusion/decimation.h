// Mesh decimation with OpenMesh's decimater: the automatic base mesh (docs/encoder-method.md
// section 1) and the encoder's correspondence proxies (a few per cent of each view's triangles).
#ifndef MESHVID_CODEC_ENC_FUSION_DECIMATION_H_
#define MESHVID_CODEC_ENC_FUSION_DECIMATION_H_

#include <cstddef>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// Settings of one decimation.
struct DecimationOptions {
  /// Stop at this many vertices (or earlier if a bound below forbids further collapses).
  std::size_t target_vertices = 1000;
  /// If > 0, also stop at this many triangles, whichever target is reached first (proxies
  /// are sized by triangles: set target_vertices = 0 to use this one alone).
  std::size_t target_triangles = 0;
  /// Largest distance (scene units) from any input vertex to the decimated surface (checked
  /// collapse by collapse, ModRemovedVertexBoundT); 0: unbounded.
  double max_error = 0;
  /// Largest angle, in degrees, between a decimated face's normal and the normals of the
  /// original faces merged into it (OpenMesh's normal-cone module); 0: unbounded. Keeps the
  /// displacement mapping between the decimated mesh and the original one-to-one. Faces
  /// never flip (turn by more than 90 degrees in one collapse) in any case.
  double max_normal_deviation_degrees = 0;
  /// Keep boundary vertices of open meshes (range images) in place. Unlocked boundaries are
  /// still held by boundary planes in the collapse priority.
  bool lock_boundary = false;
  /// If >= 1, refuse collapses that leave a triangle with an aspect ratio above this (and
  /// worse than before; OpenMesh's ModAspectRatio); 0: no shape constraint.
  double max_aspect_ratio = 0;
  /// If > 0, refuse collapses that leave an edge longer than this (scene units; a long edge
  /// stays only where the input had it); 0: unbounded. Quadrics alone collapse a straight
  /// tube into slivers running its whole length, which cannot bend with it.
  double max_edge_length = 0;
};

/// Decimates `mesh` by halfedge collapses ordered by quadric error (with the bounds above).
/// The result's vertices are a subset of the input's (positions unchanged); it has no
/// unreferenced vertices and no degenerate triangles; normals are recomputed if the input has
/// them. Triangles on an edge already used with the same orientation (non-manifold input) are
/// dropped. Deterministic and thread-safe (no shared state). Fails on an invalid mesh or
/// option.
StatusOr<TriangleMesh> DecimateMesh(const TriangleMesh& mesh, const DecimationOptions& options);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_FUSION_DECIMATION_H_
