// Fuzz target: Wavefront OBJ files (v with or without colour, vn, f with v, v/vt, v//vn,
// v/vt/vn and negative indices; polygons fan-triangulated) through ReadObj, as capture views
// and ground truth are read.
// Invariants: clean errors; a mesh read passes ValidateMesh.
#include <sstream>
#include <string>

#include "tests/fuzz/fuzz_util.h"
#include "tools/io/mesh_io.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  StatusOr<TriangleMesh> mesh = ReadObj(in, "fuzz.obj");
  if (!mesh.ok()) {
    fuzz::ExpectCleanError(mesh.status());
  } else if (!ValidateMesh(*mesh, "fuzz.obj").ok()) {
    fuzz::Fail("an OBJ mesh read is not valid");
  }
  return 0;
}
