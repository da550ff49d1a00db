#include "tools/sim/albedo.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace meshvid {
namespace {

/// An RGB colour in [0, 1] of hue `hue` (turns), fixed saturation and value.
Eigen::Vector3d HueColour(double hue) {
  constexpr double kSaturation = 0.55;
  Eigen::Vector3d rgb;
  for (int c = 0; c < 3; ++c) {
    // Each channel is a raised cosine of the hue, a third of a turn apart.
    const double phase = 2.0 * std::numbers::pi * (hue - c / 3.0);
    rgb[c] = 1.0 - kSaturation * (0.5 - 0.5 * std::cos(phase));
  }
  return rgb;
}

/// A square wave of period 1 with soft edges: 0 near the integers, 1 near the half-integers,
/// stepping smoothly over a band around each quarter (k + 0.25, k + 0.75).
double SoftSquareWave(double x) {
  constexpr double kEdge = 0.15;  // fraction of a cell taken by the edge
  const double f = x - std::floor(x);
  const double s = std::clamp((std::min(f, 1.0 - f) - 0.25) / kEdge + 0.5, 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

}  // namespace

std::vector<Colour> PaintAlbedo(const TriangleMesh& reference) {
  std::vector<Colour> colours(reference.vertex_count());
  if (reference.empty()) return colours;
  const Eigen::AlignedBox3f box = BoundingBox(reference);
  const Eigen::Vector3d lo = box.min().cast<double>();
  const Eigen::Vector3d size = box.sizes().cast<double>().cwiseMax(1e-9);
  const double cell = size.maxCoeff() / 8.0;
  for (std::size_t i = 0; i < colours.size(); ++i) {
    const Eigen::Vector3d p = reference.positions[i].cast<double>() - lo;
    const Eigen::Vector3d unit = p.cwiseQuotient(size);  // [0, 1] across the box
    const double hue = 0.55 * unit.x() + 0.35 * unit.y() + 0.2 * unit.z();
    // Checker parity as a product of three soft square waves (+1 or -1 in the cells).
    double parity = 1.0;
    for (int a = 0; a < 3; ++a) parity *= 2.0 * SoftSquareWave(p[a] / cell) - 1.0;
    const double value = 0.72 + 0.2 * parity;  // 0.52 .. 0.92
    const Eigen::Vector3d rgb = HueColour(hue) * value;
    for (int c = 0; c < 3; ++c) {
      colours[i][c] =
          static_cast<std::uint8_t>(std::clamp(std::lround(24.0 + 200.0 * rgb[c]), 24L, 224L));
    }
  }
  return colours;
}

}  // namespace meshvid
