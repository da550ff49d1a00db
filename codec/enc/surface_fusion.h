// Fusion of several range meshes of one instant (the views of one frame, in world
// coordinates) into one surface: the automatic base mesh's first step (method.md "Base mesh"),
// and the per-frame baseline of `meshvid bench`.
#ifndef MESHVID_CODEC_ENC_SURFACE_FUSION_H_
#define MESHVID_CODEC_ENC_SURFACE_FUSION_H_

#include <span>

#include "codec/common/mesh.h"
#include "codec/common/progress.h"
#include "format/status.h"

namespace meshvid {

/// Settings of the view fusion.
struct SurfaceFusionOptions {
  /// Sample spacing of the output surface in scene units; 0: derived from the data (its
  /// average point spacing).
  double spacing = 0;
  /// Most input points used; denser input is thinned on a grid first (speed bound).
  std::size_t max_points = 60000;
  /// Output triangle size bound: largest radius of a triangle's surface Delaunay ball, in
  /// spacings (CGAL's sm_radius; the default lets flat parts get large triangles).
  double max_triangle_radius = 30;
  /// Output accuracy bound: largest distance between a triangle's Delaunay-ball centre and
  /// the reconstructed implicit surface, in spacings (CGAL's sm_distance). Smaller values
  /// give more triangles where the surface curves.
  double max_surface_distance = 0.375;
  /// Memory bound: the meshing stops with an error once its Delaunay triangulation holds
  /// this many vertices (0: 10 x max_points). A Poisson function whose level set runs far
  /// from the data (inconsistent normals, thin open parts) would otherwise grow until the
  /// machine runs out of memory.
  std::size_t max_mesher_vertices = 0;
};

/// Fuses range meshes into one closed surface (watertight where the data allows), oriented
/// with normals pointing out of the captured object. Views may overlap, be noisy and have
/// holes; their triangles must face their sensor (out of the object), which orients the
/// points' normals (the views' own normals are used if present). Poisson surface
/// reconstruction (CGAL), contoured closed; the largest connected component is kept, with
/// area-weighted vertex normals. The result depends on the input only (same views, same
/// mesh, vertex for vertex). Fails if the views hold too few points or lie in one plane, or
/// if the meshing outgrows options.max_mesher_vertices.
StatusOr<TriangleMesh> FuseRangeMeshes(std::span<const TriangleMesh> views,
                                       const SurfaceFusionOptions& options = {},
                                       const ProgressCallback& progress = {});

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_SURFACE_FUSION_H_
