// Fusion of several range meshes of one instant (the views of one frame, in world
// coordinates) into one surface: the automatic base mesh of every key group
// (docs/encoder-method.md section 1), and the per-frame baseline of `meshvid bench`.
#ifndef MESHVID_CODEC_ENC_FUSION_SURFACE_FUSION_H_
#define MESHVID_CODEC_ENC_FUSION_SURFACE_FUSION_H_

#include <span>
#include <vector>

#include "codec/common/camera.h"
#include "codec/common/mesh.h"
#include "codec/common/progress.h"
#include "format/status.h"

namespace meshvid {

/// Settings of the view fusion.
struct SurfaceFusionOptions {
  /// Voxel size of the distance volume in scene units (about the output's edge length);
  /// 0: derived from the data, the views' sample spacing (or the thinning grid's cell when the
  /// input was thinned) times voxel_scale.
  double spacing = 0;
  /// Multiplies the derived voxel size (ignored when spacing is set).
  double voxel_scale = 1.0;
  /// Most input points used; denser input is thinned on a grid first (speed bound). Three
  /// 640x480 views of a body hold about 100,000.
  std::size_t max_points = 150000;
  /// Half-width of the band of voxels each point writes, in voxel sizes; (0, 7].
  double truncation_voxels = 2.5;
  /// The surface ends this many voxel sizes past the edge of the data, measured across the
  /// points' normals (see DistanceVolumeSettings::support_voxels).
  double support_voxels = 1.5;
  /// When > 0: triangles whose centre lies farther than this many of the views' sample
  /// spacings from every view vertex are removed. Where the input was thinned, the voxel is
  /// coarser than the samples and support_voxels alone lets the surface run that many coarse
  /// voxels past the edge of the data; this keeps the edge where full-resolution fusion
  /// would put it.
  double max_extension_spacings = 0;
  /// The views' cameras, in view order (empty: none known). With them the same trim also
  /// removes triangles whose centre lies in space a camera saw through (SeenFreeSpace): in
  /// front of the nearest surface its pixel met, by more than free_space_tolerance_spacings
  /// sample spacings, or where it met nothing. A sheet's surface then ends at its seen edge,
  /// while a closed body's surface turning away out of sight stays.
  std::vector<ViewCalibration> view_cameras;
  /// How far in front of what a camera saw a surface must lie to be removed, along its
  /// normal, in sample spacings (the data's noise stays within it); never less than the
  /// volume's band (truncation_voxels voxels), within which the fusion averages the views.
  double free_space_tolerance_spacings = 2;
  /// A pixel counts as seen through only when the pixels this close to it are as well.
  int free_space_margin_pixels = 0;
  /// Memory bound: the voxel size grows until the volume's estimated size fits (about 12
  /// bytes per voxel).
  std::size_t max_voxels = 20'000'000;
  /// Connected pieces with fewer than this share of the triangles are dropped (specks of
  /// noise); the largest piece is always kept.
  double min_piece_share = 0.005;
};

/// Fuses range meshes into one surface, oriented with normals pointing out of the captured
/// object. Views may overlap, be noisy and have holes; their triangles must face their sensor
/// (out of the object), which orients the points' normals (the views' own normals are used if
/// present). The points' signed distances are averaged in a sparse volume (DistanceVolume)
/// whose zero level set is contoured (ContourDistanceVolume): what the views see from all
/// sides comes out closed, what they leave open stays open (no surface is invented far from
/// the data), and the two sides of a part thicker than about two voxels stay two sheets.
/// Time and memory follow the input's size and the voxel count bound. The result depends on
/// the input only (same views, same mesh, vertex for vertex). Fails if the views hold too
/// few points, or no surface comes out (e.g. a single line of points).
StatusOr<TriangleMesh> FuseRangeMeshes(std::span<const TriangleMesh> views,
                                       const SurfaceFusionOptions& options = {},
                                       const ProgressCallback& progress = {});

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_FUSION_SURFACE_FUSION_H_
