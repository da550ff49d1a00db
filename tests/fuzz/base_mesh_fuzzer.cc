// Fuzz target: a BASE payload (a Draco mesh) through DecodeBaseMesh and the checks around it,
// as a .mvid base mesh (positions only) and as a per-frame stream with vertex colours (the
// bench's baseline player reads those from disk).
// Invariants: clean errors; a decoded mesh passes ValidateMesh (indices in range, finite,
// one colour per vertex or none).
#include "codec/dec/base_mesh_decoder.h"
#include "tests/fuzz/fuzz_util.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (VertexColours colours : {VertexColours::kIgnore, VertexColours::kRead}) {
    StatusOr<TriangleMesh> mesh =
        DecodeBaseMesh(std::span<const std::uint8_t>(data, size), colours);
    if (!mesh.ok()) {
      fuzz::ExpectCleanError(mesh.status());
      continue;
    }
    if (!ValidateMesh(*mesh, "base").ok()) fuzz::Fail("a decoded base mesh is not valid");
    if (colours == VertexColours::kIgnore && !mesh->colours.empty()) {
      fuzz::Fail("colours read where they were to be ignored");
    }
  }
  return 0;
}
