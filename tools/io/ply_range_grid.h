// Meshing of the range_grid element of Stanford range-scan PLY files (internal).
#ifndef MESHVID_TOOLS_IO_PLY_RANGE_GRID_H_
#define MESHVID_TOOLS_IO_PLY_RANGE_GRID_H_

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"
#include "format/status.h"
#include "tools/io/ply_header.h"

namespace meshvid::io_internal {

/// Meshes a Stanford range grid: `cells` holds num_cols x num_rows (obj_info of `header`)
/// vertex indices into `positions`, -1 for empty cells, rows stored bottom-up, the scanner
/// looking along -z. Triangles face the scanner (+z); silhouettes are cut by the depth-jump
/// rule. Each vertex keeps its entry of `colours` (empty: no colours). kCorrupt naming `name`
/// if the grid size is missing or wrong or nothing is meshed.
StatusOr<TriangleMesh> MeshStanfordRangeGrid(const PlyHeader& header,
                                             const std::vector<Eigen::Vector3f>& positions,
                                             const std::vector<Colour>& colours,
                                             const std::vector<std::int32_t>& cells,
                                             const std::string& name);

}  // namespace meshvid::io_internal

#endif  // MESHVID_TOOLS_IO_PLY_RANGE_GRID_H_
