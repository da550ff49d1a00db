#include "tools/io/range_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace meshvid {
namespace {

constexpr std::uint32_t kUnused = ~std::uint32_t{0};

bool IsValidSample(const RangeGrid& grid, std::size_t i) {
  const float d = grid.depth[i];
  return d > 0 && std::isfinite(d) && grid.points[i].allFinite();
}

// True if the corners' depths vary by no more than the rule's ratio of the smallest.
bool PassesDepthJumpRule(float d0, float d1, float d2, float max_ratio) {
  const float lo = std::min({d0, d1, d2});
  const float hi = std::max({d0, d1, d2});
  return hi - lo <= max_ratio * lo;
}

}  // namespace

TriangleMesh TriangulateRangeGrid(const RangeGrid& grid, const RangeGridMeshing& rule) {
  TriangleMesh mesh;
  if (grid.width < 2 || grid.height < 2) return mesh;
  const std::size_t width = static_cast<std::size_t>(grid.width);
  const std::size_t cells = width * static_cast<std::size_t>(grid.height);
  if (grid.points.size() != cells || grid.depth.size() != cells) return mesh;

  // valid[i] marks usable samples; reused afterwards as the old -> new index map.
  std::vector<std::uint32_t> index(cells);
  for (std::size_t i = 0; i < cells; ++i) index[i] = IsValidSample(grid, i) ? 0 : kUnused;

  const float ratio = rule.max_depth_jump_ratio;
  const auto& p = grid.points;
  const auto& depth = grid.depth;
  auto emit = [&](std::size_t i0, std::size_t i1, std::size_t i2) {
    if (!PassesDepthJumpRule(depth[i0], depth[i1], depth[i2], ratio)) return;
    mesh.triangles.emplace_back(static_cast<std::uint32_t>(i0), static_cast<std::uint32_t>(i1),
                                static_cast<std::uint32_t>(i2));
  };
  // Row r goes down and column c right in the image, so (r,c) -> (r+1,c) -> (r,c+1) is
  // counter-clockwise seen from the sensor.
  for (std::size_t r = 0; r + 1 < static_cast<std::size_t>(grid.height); ++r) {
    const std::size_t row = r * width;
    for (std::size_t c = 0; c + 1 < width; ++c) {
      const std::size_t a = row + c, b = a + 1, d_below = a + width, e = d_below + 1;
      if (index[a] == kUnused || index[b] == kUnused || index[d_below] == kUnused ||
          index[e] == kUnused) {
        continue;
      }
      if ((p[a] - p[e]).squaredNorm() <= (p[b] - p[d_below]).squaredNorm()) {
        emit(a, d_below, e);
        emit(a, e, b);
      } else {
        emit(a, d_below, b);
        emit(b, d_below, e);
      }
    }
  }

  // Keep referenced samples only, in grid order.
  constexpr std::uint32_t kReferenced = 1;
  for (std::size_t i = 0; i < cells; ++i) index[i] = kUnused;
  for (const Triangle& t : mesh.triangles) {
    index[t[0]] = index[t[1]] = index[t[2]] = kReferenced;
  }
  std::uint32_t next = 0;
  for (std::size_t i = 0; i < cells; ++i) {
    if (index[i] == kUnused) continue;
    index[i] = next++;
  }
  mesh.positions.resize(next);
  const bool colours = grid.colours.size() == cells;
  if (colours) mesh.colours.resize(next);
  for (std::size_t i = 0; i < cells; ++i) {
    if (index[i] == kUnused) continue;
    mesh.positions[index[i]] = p[i];
    if (colours) mesh.colours[index[i]] = grid.colours[i];
  }
  for (Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) t[k] = index[t[k]];
  }
  return mesh;
}

}  // namespace meshvid
