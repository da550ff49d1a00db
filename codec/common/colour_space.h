// The colour space of colour video: Y Cb Cr of BT.709, full range (Y and Cb, Cr in 0..255,
// chroma centred on 128), the conversion MPEG's attribute metrics use too.
#ifndef MESHVID_CODEC_COMMON_COLOUR_SPACE_H_
#define MESHVID_CODEC_COMMON_COLOUR_SPACE_H_

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Core>

namespace meshvid {

/// BT.709 luma weights of red and blue (green's is 1 - both).
inline constexpr float kLumaRed = 0.2126f;
inline constexpr float kLumaBlue = 0.0722f;

/// R G B (0..255) to Y Cb Cr (0..255, chroma centred on 128), unrounded.
inline Eigen::Vector3f RgbToYCbCr(const Eigen::Vector3f& rgb) {
  const float y = kLumaRed * rgb.x() + (1 - kLumaRed - kLumaBlue) * rgb.y() + kLumaBlue * rgb.z();
  return {y, 128.0f + (rgb.z() - y) / (2 * (1 - kLumaBlue)),
          128.0f + (rgb.x() - y) / (2 * (1 - kLumaRed))};
}

/// Y Cb Cr (as RgbToYCbCr gives them) back to R G B, unrounded and unclamped.
inline Eigen::Vector3f YCbCrToRgb(const Eigen::Vector3f& ycc) {
  const float red = ycc.x() + 2 * (1 - kLumaRed) * (ycc.z() - 128.0f);
  const float blue = ycc.x() + 2 * (1 - kLumaBlue) * (ycc.y() - 128.0f);
  const float green = (ycc.x() - kLumaRed * red - kLumaBlue * blue) / (1 - kLumaRed - kLumaBlue);
  return {red, green, blue};
}

/// Rounds each channel to 0..255.
inline Eigen::Matrix<std::uint8_t, 3, 1> RoundTo8Bits(const Eigen::Vector3f& v) {
  Eigen::Matrix<std::uint8_t, 3, 1> out;
  for (int c = 0; c < 3; ++c) {
    out[c] = static_cast<std::uint8_t>(std::clamp(std::lround(v[c]), 0L, 255L));
  }
  return out;
}

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_COLOUR_SPACE_H_
