// The one mesh file I/O module of meshvid: PLY (ascii, binary little/big endian, float or
// double, polygons triangulated, Stanford range grids) and Wavefront OBJ, with per-vertex
// normals and colours.
#ifndef MESHVID_TOOLS_IO_MESH_IO_H_
#define MESHVID_TOOLS_IO_MESH_IO_H_

#include <iosfwd>
#include <string>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// How a PLY file is written.
enum class PlyEncoding { kBinaryLittleEndian, kAscii };

/// Options for WriteMesh.
struct MeshWriteOptions {
  PlyEncoding ply_encoding = PlyEncoding::kBinaryLittleEndian;
  bool write_normals = true;  ///< write per-vertex normals when the mesh has them
  /// Write per-vertex colours when the mesh has them (PLY uchar red green blue; OBJ
  /// `v x y z r g b`, channels in [0, 1]).
  bool write_colours = true;
};

/// Reads a .ply or .obj file (chosen by extension, case-insensitive). Polygons are fan
/// triangulated. A PLY `range_grid` element (Stanford range scans) is triangulated as a
/// range grid with TriangulateRangeGrid's defaults.
/// Per-vertex colours are read from PLY `red green blue` (uchar, ushort, or float and double
/// in [0, 1]) and OBJ `v x y z r g b` (in [0, 1]). The result passes ValidateMesh; every
/// error names the file and what is wrong (missing file, truncated data, bad index, NaN...).
StatusOr<TriangleMesh> ReadMesh(const std::string& path);

/// Writes `mesh` as .ply or .obj, chosen by extension. Creates no directories.
Status WriteMesh(const std::string& path, const TriangleMesh& mesh,
                 const MeshWriteOptions& options = {});

/// PLY from a stream; `name` is used in error messages.
StatusOr<TriangleMesh> ReadPly(std::istream& in, const std::string& name);
/// OBJ from a stream; `name` is used in error messages. Reads `v`, `vn` (ignored unless one
/// per vertex) and `f` (with v, v/vt, v//vn, v/vt/vn and negative indices).
StatusOr<TriangleMesh> ReadObj(std::istream& in, const std::string& name);
/// PLY to a stream.
Status WritePly(std::ostream& out, const TriangleMesh& mesh, const MeshWriteOptions& options);
/// OBJ to a stream.
Status WriteObj(std::ostream& out, const TriangleMesh& mesh, const MeshWriteOptions& options);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_IO_MESH_IO_H_
