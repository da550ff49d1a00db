// Regular subdivision of a base mesh: the sample lattice on which displacements live.
//
// Every base triangle (v0, v1, v2) carries a lattice of points with barycentric coordinates
// (1 - i/n - j/n, i/n, j/n), 0 <= i, j, i + j <= n, n = 2^L. Points on a shared edge or at a
// shared vertex are one sample, so the subdivided mesh is watertight where the base mesh is.
// Samples are numbered level by level: the N base vertices first (level 0), then the samples
// that level 1 adds, and so on, so the samples of level l are a prefix of those of level l + 1
// and a decoder reconstructs any level up to L by reading a prefix. Within a level, edge
// samples come first (edges in order of first appearance in the triangle list, points from the
// lower to the higher vertex index), then interior samples (triangle by triangle, j-major).
#ifndef MESHVID_CODEC_COMMON_SUBDIVISION_H_
#define MESHVID_CODEC_COMMON_SUBDIVISION_H_

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// Where a sample sits on the base mesh: a triangle and barycentric weights of its corners.
struct SubdivisionSample {
  std::uint32_t triangle = 0;
  float b1 = 0;  ///< weight of corner 1 (corner 0 has 1 - b1 - b2)
  float b2 = 0;  ///< weight of corner 2
};

/// The sample lattice and per-level connectivity of a base mesh subdivided up to `levels`.
class RegularSubdivision {
 public:
  /// Largest supported level (n = 2^kMaxLevels segments per base edge).
  static constexpr int kMaxLevels = 6;

  /// Builds the lattice for `base` (its triangles only are used). Fails on an invalid mesh
  /// or levels outside 0..kMaxLevels.
  static StatusOr<RegularSubdivision> Create(const TriangleMesh& base, int levels);

  int levels() const { return levels_; }
  /// Number of samples (vertices) at level l, 0 <= l <= levels(): a prefix of all samples.
  std::size_t sample_count(int level) const { return level_sample_counts_[level]; }
  /// All samples up to the finest level, in the order described above.
  const std::vector<SubdivisionSample>& samples() const { return samples_; }
  /// The triangles of level l over sample indices; identical for every frame.
  std::vector<Triangle> Triangles(int level) const;
  /// The base mesh's triangles (corner order defines the samples' barycentric weights).
  const std::vector<Triangle>& base_triangles() const { return base_triangles_; }
  /// Number of base vertices (= sample_count(0)).
  std::size_t base_vertex_count() const { return level_sample_counts_[0]; }
  /// Segments per base edge at the finest level, 2^levels().
  int segments_per_edge() const { return n_; }
  /// The sample at lattice point (i, j) of base triangle t (0 <= i, j, i + j <= n): the
  /// point with weights (1 - i/n - j/n, i/n, j/n) of the triangle's corners.
  std::uint32_t LatticeSample(std::size_t t, int i, int j) const;

 private:
  int levels_ = 0;
  int n_ = 1;
  std::size_t points_per_triangle_ = 3;
  std::vector<std::size_t> level_sample_counts_;
  std::vector<SubdivisionSample> samples_;
  std::vector<Triangle> base_triangles_;
  std::vector<std::uint32_t> lattice_;  ///< per triangle, (n+1)(n+2)/2 sample indices
};

/// Evaluates the samples of level l on a posed base mesh: `origins` are the points on the flat
/// subdivided surface, `directions` the unit interpolated vertex normals there (eq. 3 of
/// docs/encoder-method.md, normalised so a displacement is a distance). `positions` and `normals`
/// are per base vertex (base_vertex_count() of each).
void EvaluateSampleFrames(const RegularSubdivision& subdivision, int level,
                          std::span<const Eigen::Vector3f> positions,
                          std::span<const Eigen::Vector3f> normals,
                          std::vector<Eigen::Vector3f>* origins,
                          std::vector<Eigen::Vector3f>* directions);

/// The displaced mesh of level l: sample i at origins[i] + displacements[i] * directions[i],
/// with the level's triangles. `displacements` needs at least sample_count(level) values.
TriangleMesh DisplaceSamples(const RegularSubdivision& subdivision, int level,
                             std::span<const Eigen::Vector3f> origins,
                             std::span<const Eigen::Vector3f> directions,
                             std::span<const float> displacements);

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_SUBDIVISION_H_
