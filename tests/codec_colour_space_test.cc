// Colour pictures: the BT.709 full-range conversion and the packing of a colour field into
// the displacement layout, both ways.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/common/colour_space.h"
#include "codec/common/displacement_image.h"
#include "codec/common/subdivision.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

TEST(ColourSpace, Bt709FullRangeAndBack) {
  // Reference points: white, black, and the primaries' luma.
  EXPECT_TRUE(RgbToYCbCr({255, 255, 255}).isApprox(Eigen::Vector3f(255, 128, 128), 1e-5f));
  EXPECT_TRUE(RgbToYCbCr({0, 0, 0}).isApprox(Eigen::Vector3f(0, 128, 128), 1e-5f));
  EXPECT_NEAR(RgbToYCbCr({255, 0, 0}).x(), 0.2126f * 255, 1e-3f);
  EXPECT_NEAR(RgbToYCbCr({0, 0, 255}).y(), 255.5f, 1e-3f);  // pure blue: Cb at its top
  // Every colour of a coarse grid survives 8-bit Y Cb Cr within one unit per channel.
  int worst = 0;
  for (int r = 0; r < 256; r += 15) {
    for (int g = 0; g < 256; g += 15) {
      for (int b = 0; b < 256; b += 15) {
        const Eigen::Vector3f rgb(r, g, b);
        EXPECT_TRUE(YCbCrToRgb(RgbToYCbCr(rgb)).isApprox(rgb, 1e-4f) || rgb.isZero());
        const Colour ycc = RoundTo8Bits(RgbToYCbCr(rgb));
        const Colour back = RoundTo8Bits(YCbCrToRgb(ycc.cast<float>()));
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(back[c] - int(rgb[c])));
      }
    }
  }
  EXPECT_LE(worst, 2);
}

class ColourPackingTest : public ::testing::TestWithParam<DisplacementPacking> {};

TEST_P(ColourPackingTest, EverySampleComesBackAndPaddingIsGrey) {
  const TriangleMesh base = testing::MakeGridPlane(1.0f, 3, 0.0f);
  const RegularSubdivision lattice = RegularSubdivision::Create(base, 2).value();
  const std::size_t samples = lattice.samples().size();
  std::vector<Colour> colours;
  for (std::size_t s = 0; s < samples; ++s) {
    colours.emplace_back((s * 37) % 256, (s * 11 + 60) % 256, 255 - (s * 5) % 256);
  }
  const DisplacementLayout layout = DisplacementLayout::ForSubdivision(lattice, GetParam());
  const ColourPicture picture = layout.PackColour(colours);
  ASSERT_EQ(picture.width, layout.width());
  ASSERT_EQ(picture.height, layout.height());
  for (const auto& plane : picture.planes) {
    ASSERT_EQ(plane.size(), static_cast<std::size_t>(layout.width()) * layout.height());
  }
  std::vector<Colour> back;
  layout.UnpackColour(picture, samples, &back);
  ASSERT_EQ(back.size(), samples);
  for (std::size_t s = 0; s < samples; ++s) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(back[s][c], colours[s][c], 2) << "sample " << s << " channel " << c;
    }
  }
  // A level's prefix.
  std::vector<Colour> prefix;
  layout.UnpackColour(picture, 9, &prefix);
  ASSERT_EQ(prefix.size(), 9u);
  EXPECT_TRUE(std::equal(prefix.begin(), prefix.end(), back.begin()));
  // A field shorter than the lattice leaves the samples past its end grey.
  const ColourPicture short_picture = layout.PackColour(std::span<const Colour>(colours.data(), 9));
  layout.UnpackColour(short_picture, samples, &back);
  EXPECT_EQ(back[samples - 1], Colour(128, 128, 128));
  // Lattice order leaves the picture's last pixels to padding: mid-grey.
  if (GetParam() == DisplacementPacking::kLatticeOrder) {
    ASSERT_LT(samples, picture.planes[0].size());
    for (const auto& plane : picture.planes) EXPECT_EQ(plane.back(), 128);
  }
}

INSTANTIATE_TEST_SUITE_P(BothPackings, ColourPackingTest,
                         ::testing::Values(DisplacementPacking::kLatticeOrder,
                                           DisplacementPacking::kTriangleBlocks));

}  // namespace
}  // namespace meshvid
