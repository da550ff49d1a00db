#include "codec/common/displacement_image.h"

#include <algorithm>
#include <cmath>

#include "codec/common/colour_space.h"

namespace meshvid {
namespace {

int RoundUpTo8(std::size_t v) { return static_cast<int>((v + 7) / 8 * 8); }

}  // namespace

DisplacementRange DisplacementRange::Covering(float lowest, float highest) {
  DisplacementRange range;
  range.minimum = lowest;
  range.step = (highest - lowest) / kDisplacementMaxCode;
  if (!(range.step > 0)) range.step = 1e-9f;
  return range;
}

int DisplacementRange::Quantize(float displacement) const {
  const long code = std::lround((displacement - minimum) / step);
  return static_cast<int>(std::clamp<long>(code, 0, kDisplacementMaxCode));
}

DisplacementLayout DisplacementLayout::ForSubdivision(const RegularSubdivision& subdivision,
                                                      DisplacementPacking packing) {
  DisplacementLayout layout;
  if (packing == DisplacementPacking::kLatticeOrder) {
    const std::size_t count = subdivision.samples().size();
    const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(double(count))));
    layout.width_ = std::max(64, RoundUpTo8(side));
    layout.height_ = std::max(8, RoundUpTo8((count + layout.width_ - 1) / layout.width_));
    layout.sample_of_pixel_.assign(static_cast<std::size_t>(layout.width_) * layout.height_,
                                   kPadding);
    layout.pixel_of_sample_.resize(count);
    for (std::size_t s = 0; s < count; ++s) {
      layout.sample_of_pixel_[s] = static_cast<std::uint32_t>(s);
      layout.pixel_of_sample_[s] = static_cast<std::uint32_t>(s);
    }
    return layout;
  }
  const int n = subdivision.segments_per_edge();
  const int block = n + 1;
  const std::size_t triangles = subdivision.base_triangles().size();
  const auto blocks_per_row =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(std::sqrt(double(triangles)))));
  const std::size_t block_rows = (triangles + blocks_per_row - 1) / blocks_per_row;
  layout.width_ = RoundUpTo8(blocks_per_row * block);
  layout.height_ = RoundUpTo8(block_rows * block);
  layout.sample_of_pixel_.assign(static_cast<std::size_t>(layout.width_) * layout.height_,
                                 kPadding);
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::size_t x0 = (t % blocks_per_row) * block, y0 = (t / blocks_per_row) * block;
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        // Points beyond the anti-diagonal mirror the point across it.
        const int li = i + j <= n ? i : n - j;
        const int lj = i + j <= n ? j : n - i;
        layout.sample_of_pixel_[(y0 + j) * layout.width_ + x0 + i] =
            subdivision.LatticeSample(t, li, lj);
      }
    }
  }
  // Each sample is read from its own triangle's block, at its lattice point.
  const auto& samples = subdivision.samples();
  layout.pixel_of_sample_.resize(samples.size());
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const std::size_t t = samples[s].triangle;
    const int i = static_cast<int>(std::lround(samples[s].b1 * n));
    const int j = static_cast<int>(std::lround(samples[s].b2 * n));
    const std::size_t x0 = (t % blocks_per_row) * block, y0 = (t / blocks_per_row) * block;
    layout.pixel_of_sample_[s] = static_cast<std::uint32_t>((y0 + j) * layout.width_ + x0 + i);
  }
  return layout;
}

GreyPicture DisplacementLayout::Pack(std::span<const float> displacements,
                                     const DisplacementRange& range) const {
  GreyPicture picture;
  picture.width = width_;
  picture.height = height_;
  picture.samples.resize(sample_of_pixel_.size());
  const auto zero = static_cast<std::uint16_t>(range.Quantize(0.0f));
  for (std::size_t p = 0; p < sample_of_pixel_.size(); ++p) {
    const std::uint32_t s = sample_of_pixel_[p];
    picture.samples[p] =
        s == kPadding ? zero : static_cast<std::uint16_t>(range.Quantize(displacements[s]));
  }
  return picture;
}

void DisplacementLayout::Unpack(const GreyPicture& picture, const DisplacementRange& range,
                                std::size_t count, std::vector<float>* displacements) const {
  displacements->resize(count);
  for (std::size_t s = 0; s < count; ++s) {
    const int code = std::min<int>(picture.samples[pixel_of_sample_[s]], kDisplacementMaxCode);
    (*displacements)[s] = range.Dequantize(code);
  }
}

ColourPicture DisplacementLayout::PackColour(std::span<const Colour> colours) const {
  ColourPicture picture;
  picture.width = width_;
  picture.height = height_;
  for (auto& plane : picture.planes) plane.assign(sample_of_pixel_.size(), 128);
  for (std::size_t p = 0; p < sample_of_pixel_.size(); ++p) {
    const std::uint32_t s = sample_of_pixel_[p];
    if (s == kPadding || s >= colours.size()) continue;
    const Colour ycc = RoundTo8Bits(RgbToYCbCr(colours[s].cast<float>()));
    for (int c = 0; c < 3; ++c) picture.planes[c][p] = ycc[c];
  }
  return picture;
}

void DisplacementLayout::UnpackColour(const ColourPicture& picture, std::size_t count,
                                      std::vector<Colour>* colours) const {
  colours->resize(count);
  for (std::size_t s = 0; s < count; ++s) {
    const std::uint32_t p = pixel_of_sample_[s];
    const Eigen::Vector3f ycc(picture.planes[0][p], picture.planes[1][p], picture.planes[2][p]);
    (*colours)[s] = RoundTo8Bits(YCbCrToRgb(ycc));
  }
}

}  // namespace meshvid
