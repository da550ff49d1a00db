// Packing of one frame's displacement field into a 10-bit grey picture, and of its colour
// field into an 8-bit Y Cb Cr 4:4:4 picture of the same layout, and back.
//
// Two packings, chosen per file and stated in every group's side information:
//
// Lattice order (kLatticeOrder): the samples in subdivision order (level by level) fill the
// picture row by row; width = max(64, roundup8(ceil(sqrt(S)))) for S samples, height =
// roundup8(ceil(S / width)). Few pixels; neighbouring pixels are not always neighbours on
// the surface.
//
// Triangle blocks (kTriangleBlocks): every base triangle owns a square block of
// (n+1) x (n+1) pixels, n = 2^levels. Lattice point (i, j) of the triangle (weights
// 1 - i/n - j/n, i/n, j/n of its corners) sits at pixel (i, j) of the block (x to the right,
// y down); pixels with i + j > n mirror the point (n - j, n - i) across the anti-diagonal, so
// the block is smooth where the surface is. Blocks follow the base triangles' order, left to
// right then top to bottom, ceil(sqrt(F)) blocks per row; the picture is then padded to
// multiples of 8. Samples shared by several triangles
// (edges, corners) are written in each block and read from the triangle the subdivision
// assigns them to (SubdivisionSample::triangle), so every sample has one value. About 2.5x
// the pixels of lattice order, but smooth within each block.
//
// In both, pixels that show no sample hold the code of displacement 0. Quantisation is
// uniform per group of frames: displacement = minimum + code * step.
#ifndef MESHVID_CODEC_COMMON_DISPLACEMENT_IMAGE_H_
#define MESHVID_CODEC_COMMON_DISPLACEMENT_IMAGE_H_

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/common/mesh.h"
#include "codec/common/subdivision.h"
#include "codec/common/video_codec.h"
#include "format/status.h"

namespace meshvid {

/// Largest code of a 10-bit sample.
inline constexpr int kDisplacementMaxCode = 1023;

/// Uniform quantiser of a group of frames.
struct DisplacementRange {
  float minimum = 0;
  float step = 1;

  /// The range covering [lowest, highest] with 1024 codes (a tiny positive step if equal).
  static DisplacementRange Covering(float lowest, float highest);
  float Dequantize(int code) const { return minimum + code * step; }
  int Quantize(float displacement) const;
};

/// How samples are arranged in a picture. The values are stored in files: never renumber.
enum class DisplacementPacking : std::uint8_t {
  kTriangleBlocks = 1,
  kLatticeOrder = 2,
};

/// Where every sample of a subdivision lattice sits in the displacement picture.
class DisplacementLayout {
 public:
  /// The layout of `subdivision` with `packing` (see above).
  static DisplacementLayout ForSubdivision(const RegularSubdivision& subdivision,
                                           DisplacementPacking packing);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t sample_count() const { return pixel_of_sample_.size(); }

  /// Quantises a displacement field (one value per sample) into a picture.
  GreyPicture Pack(std::span<const float> displacements, const DisplacementRange& range) const;
  /// De-quantises the first `count` samples (a level's prefix) of a picture of this layout.
  void Unpack(const GreyPicture& picture, const DisplacementRange& range, std::size_t count,
              std::vector<float>* displacements) const;

  /// Puts a colour field (one R G B colour per sample) into a colour picture of this layout,
  /// as Y Cb Cr (colour_space.h); pixels that show no sample, or a sample past the end of
  /// `colours`, are mid-grey (128, 128, 128).
  ColourPicture PackColour(std::span<const Colour> colours) const;
  /// The R G B colours of the first `count` samples of a colour picture of this layout.
  void UnpackColour(const ColourPicture& picture, std::size_t count,
                    std::vector<Colour>* colours) const;

 private:
  static constexpr std::uint32_t kPadding = ~std::uint32_t{0};
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint32_t> pixel_of_sample_;  ///< the pixel a sample is read from
  std::vector<std::uint32_t> sample_of_pixel_;  ///< the sample a pixel shows, or kPadding
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_DISPLACEMENT_IMAGE_H_
