// RgbImage: an 8-bit RGB picture, with what `meshvid render` draws on it besides the surface
// (text in a built-in 5x7 pixel font, filled rectangles, side-by-side panels) and PNG output.
#ifndef MESHVID_TOOLS_RENDER_RGB_IMAGE_H_
#define MESHVID_TOOLS_RENDER_RGB_IMAGE_H_

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// One 8-bit RGB colour.
using Rgb = std::array<std::uint8_t, 3>;

/// A picture, row-major, 3 bytes a pixel, top row first.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;

  RgbImage() = default;
  /// A `width` x `height` picture filled with `fill`.
  RgbImage(int width, int height, Rgb fill = {0, 0, 0});
  std::uint8_t* at(int x, int y) { return &pixels[3 * (static_cast<std::size_t>(y) * width + x)]; }
  const std::uint8_t* at(int x, int y) const {
    return &pixels[3 * (static_cast<std::size_t>(y) * width + x)];
  }
  void Set(int x, int y, Rgb c);  ///< ignores pixels outside the picture
};

/// Fills the rectangle [x, x + w) x [y, y + h), clipped to the picture.
void FillRect(RgbImage* image, int x, int y, int w, int h, Rgb colour);

/// Draws `text` with its top-left corner at (x, y), each font pixel `scale` x `scale` pixels,
/// one pixel of `shadow` below-right for legibility on any background. Letters are drawn in
/// upper case; characters the font lacks are drawn as spaces. Returns the width drawn.
int DrawText(RgbImage* image, int x, int y, std::string_view text, Rgb colour, int scale = 2,
             Rgb shadow = {0, 0, 0});
/// The width DrawText would take.
int TextWidth(std::string_view text, int scale = 2);

/// Places `panels` (of equal height) left to right.
RgbImage SideBySide(const std::vector<RgbImage>& panels);

/// The picture as PNG bytes (8-bit RGB).
StatusOr<std::string> EncodePng(const RgbImage& image);
/// Writes the picture as a PNG file (parent folders created, written atomically).
Status WritePng(const std::string& path, const RgbImage& image);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_RENDER_RGB_IMAGE_H_
