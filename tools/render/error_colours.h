// Colouring a surface by its distance to ground truth, and the colour bar (in millimetres,
// scene units taken as metres) that explains the colours.
#ifndef MESHVID_TOOLS_RENDER_ERROR_COLOURS_H_
#define MESHVID_TOOLS_RENDER_ERROR_COLOURS_H_

#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"
#include "tools/eval/surface_distance.h"
#include "tools/render/rgb_image.h"

namespace meshvid {

/// The colour of `t` in [0, 1] (clamped) on a blue (0) - yellow - red (1) scale.
Eigen::Vector3f ErrorColour(float t);

/// Distance of every vertex of `mesh` to `reference`, in parallel (scene units).
std::vector<float> VertexDistances(const TriangleMesh& mesh, const SurfaceDistance& reference);

/// ErrorColour(distance / max_distance) of every distance.
std::vector<Eigen::Vector3f> ErrorColours(const std::vector<float>& distances,
                                          float max_distance);

/// Draws a vertical colour bar for [0, max_mm] millimetres at the right edge of `image`, with
/// its scale labelled.
void DrawColourBar(RgbImage* image, float max_mm);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_RENDER_ERROR_COLOURS_H_
