// Fuzz target: a group's side information (packing, displacement range, video configuration,
// the zstd-coded transform block) through DecodeGofSideInfo. Input: u32 frame_count (the GOF
// chunk's), u32 segment_count (the MOTN's), then the side information bytes.
// Invariants: clean errors; a decoded group has frame_count x segment_count finite
// transforms and a positive finite displacement step.
#include <cmath>

#include "codec/dec/gof_side_info.h"
#include "tests/fuzz/fuzz_util.h"

using namespace meshvid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::FuzzInput input(data, size);
  const std::uint32_t frame_count = input.U32();
  const std::uint32_t segment_count = input.U32();
  StatusOr<GofSideInfo> side =
      DecodeGofSideInfo(input.Rest(), frame_count, segment_count, MotionQuantization{});
  if (!side.ok()) {
    fuzz::ExpectCleanError(side.status());
    return 0;
  }
  if (side->transforms.size() != frame_count) fuzz::Fail("transform frames differ");
  for (const auto& frame : side->transforms) {
    if (frame.size() != segment_count) fuzz::Fail("transform segments differ");
    for (const RigidTransform& t : frame) {
      if (!t.translation.allFinite() || !t.rotation.coeffs().allFinite()) {
        fuzz::Fail("a decoded transform is not finite");
      }
    }
  }
  if (!(side->displacement_range.step > 0) || !std::isfinite(side->displacement_range.step)) {
    fuzz::Fail("displacement step is not positive and finite");
  }
  return 0;
}
