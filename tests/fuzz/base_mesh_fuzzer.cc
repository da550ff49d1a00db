// Fuzz target: a BASE payload (a Draco mesh) through DecodeBaseMesh and the checks around it.
// Invariants: clean errors; a decoded mesh passes ValidateMesh (indices in range, finite).
#include "codec/dec/base_mesh_decoder.h"
#include "tests/fuzz/fuzz_util.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  StatusOr<TriangleMesh> mesh = DecodeBaseMesh(std::span<const std::uint8_t>(data, size));
  if (!mesh.ok()) {
    fuzz::ExpectCleanError(mesh.status());
    return 0;
  }
  if (!ValidateMesh(*mesh, "base").ok()) fuzz::Fail("a decoded base mesh is not valid");
  return 0;
}
