// Internal entry points of the mesh I/O module: parsers over an in-memory file image, shared by
// the stream and path front ends in mesh_io.cc. Not part of the public API.
#ifndef MESHVID_TOOLS_IO_MESH_IO_INTERNAL_H_
#define MESHVID_TOOLS_IO_MESH_IO_INTERNAL_H_

#include <istream>
#include <string>
#include <string_view>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid::io_internal {

/// Parses a whole PLY file image; `name` prefixes every error message.
StatusOr<TriangleMesh> ParsePly(std::string_view data, const std::string& name);

/// Parses a whole OBJ file image; `name` prefixes every error message.
StatusOr<TriangleMesh> ParseObj(std::string_view data, const std::string& name);

/// Reads everything left in `in` into a string (kIoError naming `name` on a stream failure).
StatusOr<std::string> ReadAll(std::istream& in, const std::string& name);

}  // namespace meshvid::io_internal

#endif  // MESHVID_TOOLS_IO_MESH_IO_INTERNAL_H_
