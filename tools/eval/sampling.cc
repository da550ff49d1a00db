#include "tools/eval/sampling.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "codec/common/counter_random.h"

namespace meshvid {

std::uint64_t MixSeed(std::uint64_t seed, std::uint64_t value) {
  return SplitMix64(SplitMix64(seed) ^ (value * 0xD1B54A32D192ED03ull));
}

double UniformHash(std::uint64_t seed, std::uint64_t index, std::uint64_t stream) {
  return UniformClosedOpen(SplitMix64(MixSeed(seed, stream) ^ SplitMix64(index)));
}

StatusOr<SurfaceSamples> SampleSurface(const TriangleMesh& mesh, std::size_t count,
                                       std::uint64_t seed) {
  if (count == 0) return InvalidArgumentError("the sample count must be positive");
  const std::size_t n = mesh.triangle_count();
  // cumulative[t] = area of triangles 0..t (inclusive).
  std::vector<double> cumulative(n);
  double total = 0.0;
  for (std::size_t t = 0; t < n; ++t) {
    const Triangle& tri = mesh.triangles[t];
    const Eigen::Vector3d a = mesh.positions[tri[0]].cast<double>();
    const Eigen::Vector3d b = mesh.positions[tri[1]].cast<double>();
    const Eigen::Vector3d c = mesh.positions[tri[2]].cast<double>();
    total += 0.5 * (b - a).cross(c - a).norm();
    cumulative[t] = total;
  }
  if (!(total > 0.0) || !std::isfinite(total)) {
    return InvalidArgumentError("cannot sample a surface with no area (" + std::to_string(n) +
                                " triangles, all degenerate or none)");
  }

  SurfaceSamples samples;
  samples.points.resize(count);
  samples.normals.resize(count);
  samples.triangles.resize(count);
  const double step = total / static_cast<double>(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const double u = (static_cast<double>(i) + UniformHash(seed, i, 0)) * step;
      // The first triangle whose cumulative area exceeds u (never a zero-area one).
      std::size_t t = std::upper_bound(cumulative.begin(), cumulative.end(), u) -
                      cumulative.begin();
      t = std::min(t, n - 1);
      while (t > 0 && cumulative[t] == cumulative[t - 1]) --t;  // rounding at the very end
      const Triangle& tri = mesh.triangles[t];
      const Eigen::Vector3d a = mesh.positions[tri[0]].cast<double>();
      const Eigen::Vector3d b = mesh.positions[tri[1]].cast<double>();
      const Eigen::Vector3d c = mesh.positions[tri[2]].cast<double>();
      // Uniform point in the triangle: s = sqrt(r1) folds the square onto it.
      const double s = std::sqrt(UniformHash(seed, i, 1));
      const double r = UniformHash(seed, i, 2);
      const Eigen::Vector3d p = a + s * (1.0 - r) * (b - a) + s * r * (c - a);
      samples.points[i] = p.cast<float>();
      samples.normals[i] = TriangleNormal(mesh, t);
      samples.triangles[i] = static_cast<std::uint32_t>(t);
    }
  });
  return samples;
}

}  // namespace meshvid
