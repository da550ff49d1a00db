#include "tools/render/error_colours.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meshvid {

Eigen::Vector3f ErrorColour(float t) {
  // Blue, light blue, pale yellow, orange, dark red at evenly spaced stops.
  static const Eigen::Vector3f kStops[] = {{0.19f, 0.21f, 0.58f},
                                           {0.45f, 0.68f, 0.82f},
                                           {1.00f, 0.88f, 0.56f},
                                           {0.96f, 0.43f, 0.26f},
                                           {0.65f, 0.00f, 0.15f}};
  constexpr int kLast = 4;
  if (!(t > 0)) return kStops[0];
  if (t >= 1) return kStops[kLast];
  const float x = t * kLast;
  const int i = std::min(static_cast<int>(x), kLast - 1);
  const float f = x - static_cast<float>(i);
  return (1 - f) * kStops[i] + f * kStops[i + 1];
}

std::vector<float> VertexDistances(const TriangleMesh& mesh, const SurfaceDistance& reference) {
  std::vector<float> distances(mesh.vertex_count());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, distances.size(), 512),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i) {
                        distances[i] = static_cast<float>(reference.Distance(mesh.positions[i]));
                      }
                    });
  return distances;
}

std::vector<Eigen::Vector3f> ErrorColours(const std::vector<float>& distances,
                                          float max_distance) {
  std::vector<Eigen::Vector3f> colours(distances.size());
  for (std::size_t i = 0; i < distances.size(); ++i) {
    colours[i] = ErrorColour(max_distance > 0 ? distances[i] / max_distance : 0.0f);
  }
  return colours;
}

void DrawColourBar(RgbImage* image, float max_mm) {
  const int scale = image->height >= 400 ? 2 : 1;
  const int bar_width = 14 * scale;
  const int top = 28 * scale, bottom = image->height - 16 * scale;
  if (bottom - top < 20) return;
  char labels[3][32];
  for (int k = 0; k < 3; ++k) std::snprintf(labels[k], sizeof labels[k], "%.3g", max_mm * (2 - k) / 2);
  int label_width = 0;
  for (const char* label : labels) label_width = std::max(label_width, TextWidth(label, scale));
  const int x = image->width - bar_width - label_width - 10 * scale;
  const Rgb white = {235, 235, 235};
  DrawText(image, x, top - 12 * scale, "MM", white, scale);
  FillRect(image, x - 1, top - 1, bar_width + 2, bottom - top + 2, {20, 20, 20});
  for (int y = top; y < bottom; ++y) {
    const Eigen::Vector3f c = ErrorColour(static_cast<float>(bottom - 1 - y) / (bottom - top - 1));
    FillRect(image, x, y, bar_width, 1,
             {static_cast<std::uint8_t>(255 * c.x()), static_cast<std::uint8_t>(255 * c.y()),
              static_cast<std::uint8_t>(255 * c.z())});
  }
  for (int k = 0; k < 3; ++k) {
    const int y = top + (bottom - 1 - top) * k / 2;
    FillRect(image, x + bar_width, y, 2 * scale, 1, white);
    DrawText(image, x + bar_width + 5 * scale + 1, y - 3 * scale, labels[k], white, scale);
  }
}

}  // namespace meshvid
