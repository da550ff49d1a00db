// The zero level set of a DistanceVolume as a triangle mesh.
#ifndef MESHVID_CODEC_ENC_FUSION_CONTOUR_VOLUME_H_
#define MESHVID_CODEC_ENC_FUSION_CONTOUR_VOLUME_H_

#include "codec/common/mesh.h"
#include "codec/enc/fusion/distance_volume.h"

namespace meshvid {

/// Contours the volume's zero level set by marching tetrahedra: every grid cube whose 8
/// corners the data supports is cut into the 6 tetrahedra around its main diagonal (the same
/// cut in neighbouring cubes, so the surface has no cracks), and each tetrahedron the level set
/// crosses gives one or two triangles. Cubes with an unsupported corner give nothing, so the
/// surface ends where the data ends. Triangles face the positive (outside) side; vertices on a
/// grid edge are shared, so the mesh is edge-manifold; zero-area triangles are dropped. Element
/// order follows the volume's block order.
TriangleMesh ContourDistanceVolume(const DistanceVolume& volume);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_FUSION_CONTOUR_VOLUME_H_
