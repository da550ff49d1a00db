// Fuzz target: PLY files (ascii, binary little and big endian, float or double, polygons,
// vertex colours, Stanford range grids) through ReadPly, as capture views are read.
// Invariants: clean errors; a mesh read passes ValidateMesh.
#include <sstream>
#include <string>

#include "tests/fuzz/fuzz_util.h"
#include "tools/io/mesh_io.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  StatusOr<TriangleMesh> mesh = ReadPly(in, "fuzz.ply");
  if (!mesh.ok()) {
    fuzz::ExpectCleanError(mesh.status());
  } else if (!ValidateMesh(*mesh, "fuzz.ply").ok()) {
    fuzz::Fail("a PLY mesh read is not valid");
  }
  return 0;
}
