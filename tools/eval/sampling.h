// Dense, area-weighted, reproducible sampling of a triangle surface: the point sets the
// evaluation's point-to-point (D1) and point-to-plane (D2) metrics compare.
#ifndef MESHVID_TOOLS_EVAL_SAMPLING_H_
#define MESHVID_TOOLS_EVAL_SAMPLING_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// Points on a surface, each with the unit normal and index of the triangle it lies on.
struct SurfaceSamples {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;
  std::vector<std::uint32_t> triangles;

  std::size_t size() const { return points.size(); }
};

/// A uniform random number in [0, 1) that depends only on (seed, index, stream): a
/// counter-based generator, so samples do not depend on thread scheduling.
double UniformHash(std::uint64_t seed, std::uint64_t index, std::uint64_t stream);

/// Mixes two numbers into a new seed (e.g. a user seed and a frame number).
std::uint64_t MixSeed(std::uint64_t seed, std::uint64_t value);

/// Draws `count` points uniformly by area on `mesh`. Stratified on the cumulative area: sample
/// i falls in the area interval [i, i+1) * A / count at a random position, so every triangle
/// gets its area share of the samples to within one, and the result depends only on the mesh,
/// `count` and `seed` (the same seed on the same mesh gives the same points). Degenerate
/// triangles get no samples. Fails if count is 0 or the mesh has no area.
StatusOr<SurfaceSamples> SampleSurface(const TriangleMesh& mesh, std::size_t count,
                                       std::uint64_t seed);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_EVAL_SAMPLING_H_
