// Fuzz target: a MOTN payload (segments, blend weights, surface mask) through
// DecodeMotionModel. Input: u32 vertex_count, u32 triangle_count (what the key group's base
// mesh would give; bounded to 2^20 as a decoded Draco mesh's would be), then the payload.
// Invariants: clean errors; a decoded model passes ValidateMotionModel and has one blend per
// vertex and a mask of 0 or triangle_count entries; a deformation-node model (version 3) has
// one base vertex per segment and no blends, and on a strip of vertex_count vertices (up to
// 4096) its derived blends are a clean error or a valid model.
#include "codec/common/deformation_graph.h"
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
  MotionModel& model = motion->model;
  if (!model.node_vertices.empty()) {
    if (!model.blends.empty() || model.node_vertices.size() != model.segment_count) {
      fuzz::Fail("a node model has blends or a node count other than its segments'");
    }
    for (std::uint32_t v : model.node_vertices) {
      if (v >= vertex_count) fuzz::Fail("node vertex out of range");
    }
    if (vertex_count > 4096) return 0;
    TriangleMesh strip;
    for (std::size_t i = 0; i < vertex_count; ++i) {
      strip.positions.emplace_back(float(i / 2), float(i % 2), 0.0f);
      if (i >= 2) {
        const auto a = static_cast<std::uint32_t>(i);
        strip.triangles.push_back({a - 2, a - 1, a});
      }
    }
    const Status derived = CompleteNodeBlends(strip, &model);
    if (!derived.ok()) {
      fuzz::ExpectCleanError(derived);
      return 0;
    }
  }
  if (model.blends.size() != vertex_count) fuzz::Fail("blend count differs from vertex count");
  if (!model.surface_triangles.empty() && model.surface_triangles.size() != triangle_count) {
    fuzz::Fail("surface mask size differs from triangle count");
  }
  if (!ValidateMotionModel(model, vertex_count).ok()) fuzz::Fail("decoded model is not valid");
  return 0;
}
