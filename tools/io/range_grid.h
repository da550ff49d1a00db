// Meshing of range images: a grid of 3D samples (from a depth image, a Stanford range_grid or
// the simulator) turned into a triangle mesh that is split at depth discontinuities.
#ifndef MESHVID_TOOLS_IO_RANGE_GRID_H_
#define MESHVID_TOOLS_IO_RANGE_GRID_H_

#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"

namespace meshvid {

/// A width x height grid of samples, row-major. A sample is valid if depth > 0.
struct RangeGrid {
  int width = 0;
  int height = 0;
  std::vector<Eigen::Vector3f> points;  ///< width * height positions (any frame)
  std::vector<float> depth;             ///< width * height distances along the view axis
  std::vector<Colour> colours;          ///< empty, or width * height colours
};

/// The depth-jump rule deciding which grid triangles are kept.
struct RangeGridMeshing {
  /// A triangle is dropped when (max depth - min depth) of its corners exceeds this ratio of
  /// its smallest depth: a discontinuity (silhouette, occlusion edge) rather than surface.
  float max_depth_jump_ratio = 0.03f;
};

/// Triangulates every grid cell whose corners are valid into two triangles (choosing the
/// shorter diagonal), dropping triangles that break the depth-jump rule, then removes
/// unreferenced samples (the mesh keeps the grid's colours, if any). Triangles face the sensor
/// (counter-clockwise seen from it, for a grid with rows going down and columns going right in the
/// image). The result may be empty.
TriangleMesh TriangulateRangeGrid(const RangeGrid& grid, const RangeGridMeshing& rule = {});

}  // namespace meshvid

#endif  // MESHVID_TOOLS_IO_RANGE_GRID_H_
