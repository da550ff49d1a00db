// Fuzz target: a MOTN payload (segments, blend weights, surface mask) through
// DecodeMotionModel. Input: u32 vertex_count, u32 triangle_count (what the key group's base
// mesh would give; bounded to 2^20 as a decoded Draco mesh's would be), then the payload.
// Invariants: clean errors; a decoded model passes ValidateMotionModel and has one blend per
// vertex and a mask of 0 or triangle_count entries.
#include "codec/common/motion.h"
#include "codec/dec/motion_decoder.h"
#include "tests/fuzz/fuzz_util.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::FuzzInput input(data, size);
  const std::size_t vertex_count = input.U32() % (1u << 20);
  const std::size_t triangle_count = input.U32() % (1u << 21);
  StatusOr<DecodedMotion> motion = DecodeMotionModel(input.Rest(), vertex_count, triangle_count);
  if (!motion.ok()) {
    fuzz::ExpectCleanError(motion.status());
    return 0;
  }
  const MotionModel& model = motion->model;
  if (model.blends.size() != vertex_count) fuzz::Fail("blend count differs from vertex count");
  if (!model.surface_triangles.empty() && model.surface_triangles.size() != triangle_count) {
    fuzz::Fail("surface mask size differs from triangle count");
  }
  if (!ValidateMotionModel(model, vertex_count).ok()) fuzz::Fail("decoded model is not valid");
  return 0;
}
