#include "codec/common/subdivision.h"

#include <algorithm>
#include <bit>
#include <map>
#include <string>
#include <utility>

namespace meshvid {
namespace {

/// The level at which lattice point (i, j) of a triangle with n = 2^levels first appears.
int PointLevel(int i, int j, int levels) {
  const int k = (1 << levels) - i - j;
  int trailing = levels;
  for (int c : {i, j, k}) {
    if (c != 0) trailing = std::min(trailing, std::countr_zero(static_cast<unsigned>(c)));
  }
  return levels - trailing;
}

/// Index of lattice point (i, j) in a triangle's row-major (j-major) lattice of side n.
std::size_t LatticeOffset(int i, int j, int n) {
  // Rows j = 0..n hold n + 1 - j points each.
  return static_cast<std::size_t>(j) * (n + 1) - static_cast<std::size_t>(j) * (j - 1) / 2 + i;
}

}  // namespace

StatusOr<RegularSubdivision> RegularSubdivision::Create(const TriangleMesh& base, int levels) {
  MESHVID_RETURN_IF_ERROR(ValidateMesh(base, "base mesh"));
  if (levels < 0 || levels > kMaxLevels) {
    return InvalidArgumentError("subdivision levels must be in 0.." +
                                std::to_string(kMaxLevels) + ", got " + std::to_string(levels));
  }
  RegularSubdivision s;
  s.levels_ = levels;
  s.n_ = 1 << levels;
  const int n = s.n_;
  s.points_per_triangle_ = static_cast<std::size_t>(n + 1) * (n + 2) / 2;
  constexpr std::uint32_t kUnassigned = ~std::uint32_t{0};
  s.lattice_.assign(base.triangle_count() * s.points_per_triangle_, kUnassigned);

  // Corner samples: the base vertices keep their indices.
  s.samples_.resize(base.vertex_count());
  std::vector<bool> vertex_seen(base.vertex_count(), false);
  for (std::size_t t = 0; t < base.triangle_count(); ++t) {
    const Triangle& tri = base.triangles[t];
    const int corner_i[3] = {0, n, 0}, corner_j[3] = {0, 0, n};
    for (int c = 0; c < 3; ++c) {
      s.lattice_[t * s.points_per_triangle_ + LatticeOffset(corner_i[c], corner_j[c], n)] = tri[c];
      if (!vertex_seen[tri[c]]) {
        vertex_seen[tri[c]] = true;
        s.samples_[tri[c]] = {static_cast<std::uint32_t>(t), corner_i[c] / float(n),
                              corner_j[c] / float(n)};
      }
    }
  }
  s.level_sample_counts_.push_back(base.vertex_count());

  // Edges in order of first appearance, keyed by (lower, higher) vertex index.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> edge_index;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const Triangle& tri : base.triangles) {
    for (int c = 0; c < 3; ++c) {
      const auto key = std::minmax(tri[c], tri[(c + 1) % 3]);
      if (edge_index.emplace(key, edges.size()).second) edges.push_back(key);
    }
  }
  // For each edge, the sample index of its point at parameter p/n from the lower vertex.
  std::vector<std::uint32_t> edge_points(edges.size() * (n + 1), kUnassigned);
  std::vector<bool> sample_placed(base.vertex_count(), true);  // corners are placed above

  // Maps lattice point (i, j) of triangle t to (edge, parameter from the lower vertex), or
  // returns false for an interior point.
  auto on_edge = [&](std::size_t t, int i, int j, std::size_t* edge, int* param) {
    const Triangle& tri = base.triangles[t];
    const int k = n - i - j;
    // Barycentric weights in units of 1/n: corner0 k, corner1 i, corner2 j.
    int a, b, wa;
    if (j == 0) { a = 0; b = 1; wa = k; }
    else if (k == 0) { a = 1; b = 2; wa = i; }
    else if (i == 0) { a = 2; b = 0; wa = j; }
    else return false;
    const std::uint32_t va = tri[a], vb = tri[b];
    *edge = edge_index.at(std::minmax(va, vb));
    // The parameter runs from the lower vertex: the weight of the higher one.
    *param = va < vb ? n - wa : wa;
    return true;
  };

  for (int level = 1; level <= levels; ++level) {
    // Edge samples of this level.
    const int step = 1 << (levels - level);
    for (std::size_t e = 0; e < edges.size(); ++e) {
      for (int p = step; p < n; p += 2 * step) {
        edge_points[e * (n + 1) + p] = static_cast<std::uint32_t>(s.samples_.size());
        s.samples_.push_back({});  // placed on the first triangle that reaches it, below
        sample_placed.push_back(false);
      }
    }
    // Interior samples of this level, and lattice entries of this level's edge samples.
    for (std::size_t t = 0; t < base.triangle_count(); ++t) {
      for (int j = 0; j <= n; j += step) {
        for (int i = 0; i + j <= n; i += step) {
          if (PointLevel(i, j, levels) != level) continue;
          std::uint32_t& slot = s.lattice_[t * s.points_per_triangle_ + LatticeOffset(i, j, n)];
          std::size_t edge;
          int param;
          const SubdivisionSample sample{static_cast<std::uint32_t>(t), i / float(n),
                                         j / float(n)};
          if (on_edge(t, i, j, &edge, &param)) {
            slot = edge_points[edge * (n + 1) + param];
            if (!sample_placed[slot]) {
              s.samples_[slot] = sample;
              sample_placed[slot] = true;
            }
          } else {
            slot = static_cast<std::uint32_t>(s.samples_.size());
            s.samples_.push_back(sample);
            sample_placed.push_back(true);
          }
        }
      }
    }
    s.level_sample_counts_.push_back(s.samples_.size());
  }
  s.base_triangles_ = base.triangles;
  return s;
}

std::uint32_t RegularSubdivision::LatticeSample(std::size_t t, int i, int j) const {
  return lattice_[t * points_per_triangle_ + LatticeOffset(i, j, n_)];
}

std::vector<Triangle> RegularSubdivision::Triangles(int level) const {
  const int step = 1 << (levels_ - level);
  const std::size_t base_triangles = lattice_.size() / points_per_triangle_;
  std::vector<Triangle> triangles;
  triangles.reserve(base_triangles << (2 * level));
  for (std::size_t t = 0; t < base_triangles; ++t) {
    for (int j = 0; j < n_; j += step) {
      for (int i = 0; i + j < n_; i += step) {
        triangles.emplace_back(LatticeSample(t, i, j), LatticeSample(t, i + step, j),
                               LatticeSample(t, i, j + step));
        if (i + j + 2 * step <= n_) {
          triangles.emplace_back(LatticeSample(t, i + step, j),
                                 LatticeSample(t, i + step, j + step),
                                 LatticeSample(t, i, j + step));
        }
      }
    }
  }
  return triangles;
}

void EvaluateSampleFrames(const RegularSubdivision& subdivision, int level,
                          std::span<const Eigen::Vector3f> positions,
                          std::span<const Eigen::Vector3f> normals,
                          std::vector<Eigen::Vector3f>* origins,
                          std::vector<Eigen::Vector3f>* directions) {
  const std::size_t count = subdivision.sample_count(level);
  origins->resize(count);
  directions->resize(count);
  const auto& samples = subdivision.samples();
  const auto& triangles = subdivision.base_triangles();
  for (std::size_t s = 0; s < count; ++s) {
    const SubdivisionSample& sample = samples[s];
    const Triangle& tri = triangles[sample.triangle];
    const float b0 = 1.0f - sample.b1 - sample.b2;
    (*origins)[s] =
        b0 * positions[tri[0]] + sample.b1 * positions[tri[1]] + sample.b2 * positions[tri[2]];
    const Eigen::Vector3f normal =
        b0 * normals[tri[0]] + sample.b1 * normals[tri[1]] + sample.b2 * normals[tri[2]];
    const float length = normal.norm();
    (*directions)[s] = length > 0 ? Eigen::Vector3f(normal / length) : Eigen::Vector3f::Zero();
  }
}

TriangleMesh DisplaceSamples(const RegularSubdivision& subdivision, int level,
                             std::span<const Eigen::Vector3f> origins,
                             std::span<const Eigen::Vector3f> directions,
                             std::span<const float> displacements) {
  TriangleMesh mesh;
  const std::size_t count = subdivision.sample_count(level);
  mesh.positions.resize(count);
  for (std::size_t s = 0; s < count; ++s) {
    mesh.positions[s] = origins[s] + displacements[s] * directions[s];
  }
  mesh.triangles = subdivision.Triangles(level);
  return mesh;
}

}  // namespace meshvid
