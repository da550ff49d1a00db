// Tests of the displacement picture's padding pixels (spec/mvid-codec.md, "Layout of a
// picture"): they hold the code of displacement 0, clamped to 0..1023 when 0 is outside the
// group's range, and the samples around them are unaffected.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "codec/common/displacement_image.h"
#include "codec/common/subdivision.h"
#include "tests/analytic_mvid.h"

namespace meshvid {
namespace {

/// The codes of the pixels that show no sample, and checks the others against `displacements`.
std::vector<int> PaddingCodes(const DisplacementLayout& layout, const std::vector<float>& displacements,
                              const DisplacementRange& range) {
  const GreyPicture picture = layout.Pack(displacements, range);
  std::vector<float> unpacked;
  layout.Unpack(picture, range, displacements.size(), &unpacked);
  for (std::size_t s = 0; s < displacements.size(); ++s) {
    EXPECT_NEAR(unpacked[s], displacements[s], range.step) << "sample " << s;
  }
  // A pixel is padding if changing every sample's value leaves it alone.
  std::vector<float> shifted = displacements;
  for (float& d : shifted) d = range.Dequantize(range.Quantize(d) == 0 ? 1 : 0);
  const GreyPicture other = layout.Pack(shifted, range);
  std::vector<int> codes;
  for (std::size_t p = 0; p < picture.samples.size(); ++p) {
    if (picture.samples[p] == other.samples[p]) codes.push_back(picture.samples[p]);
  }
  return codes;
}

class PaddingTest : public ::testing::TestWithParam<DisplacementPacking> {};

TEST_P(PaddingTest, PaddingHoldsTheCodeOfZeroClampedToTheRange) {
  auto lattice = RegularSubdivision::Create(testing::LatLongSphere(3, 8), 2);
  ASSERT_TRUE(lattice.ok()) << lattice.status().ToString();
  const DisplacementLayout layout = DisplacementLayout::ForSubdivision(*lattice, GetParam());
  ASSERT_GT(std::size_t(layout.width()) * layout.height(), layout.sample_count());

  struct Case {
    float lowest, highest;
    int padding;  ///< the code the spec gives padding pixels
  };
  const Case cases[] = {
      {-1.0f, 3.0f, 256},    // 0 inside: round(1 / (4 / 1023)) = round(255.75)
      {0.5f, 2.0f, 0},       // 0 below the range: the lowest code
      {-3.0f, -0.25f, 1023}  // 0 above the range: the highest code
  };
  for (const Case& c : cases) {
    const DisplacementRange range = DisplacementRange::Covering(c.lowest, c.highest);
    std::vector<float> displacements(layout.sample_count());
    for (std::size_t s = 0; s < displacements.size(); ++s) {
      displacements[s] = c.lowest + (c.highest - c.lowest) * float(s % 7) / 6;
    }
    const std::vector<int> codes = PaddingCodes(layout, displacements, range);
    ASSERT_FALSE(codes.empty());
    for (int code : codes) EXPECT_EQ(code, c.padding) << "range " << c.lowest << ".." << c.highest;
  }
}

INSTANTIATE_TEST_SUITE_P(BothPackings, PaddingTest,
                         ::testing::Values(DisplacementPacking::kLatticeOrder,
                                           DisplacementPacking::kTriangleBlocks));

}  // namespace
}  // namespace meshvid
