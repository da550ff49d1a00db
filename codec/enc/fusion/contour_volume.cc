#include "codec/enc/fusion/contour_volume.h"

#include <array>
#include <cstdint>
#include <unordered_map>
#include <utility>

namespace meshvid {
namespace {

// The 6 tetrahedra of a cube around its diagonal from corner 0 to corner 7: one per order in
// which the path 0 -> 7 takes the three axes (corner c is at (c & 1, c >> 1 & 1, c >> 2 & 1)).
// Every edge goes from a corner to one with more bits set, so an edge is named by its lower
// corner and the direction bits it adds.
constexpr std::array<std::array<int, 4>, 6> kTetrahedra = {{
    {0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7},
}};

// Voxel coordinates are packed in 20 bits each, offset so that negative ones fit.
constexpr int kPackBits = 20;
constexpr int kPackOffset = 1 << (kPackBits - 1);

class TetrahedraMesher {
 public:
  explicit TetrahedraMesher(const DistanceVolume& volume) : volume_(volume) {
    // A rough estimate of the vertex count (it only saves rehashing as the map grows).
    vertex_of_edge_.reserve(volume.voxel_count() / 16);
  }

  void AddCube(const VoxelIndex& v, const float distances[8]) {
    for (const std::array<int, 4>& tet : kTetrahedra) AddTetrahedron(v, tet, distances);
  }

  TriangleMesh Take() { return std::move(mesh_); }

 private:
  // The mesh vertex where the level set crosses the edge between corners a and b (a's bits a
  // subset of b's) of the cube at v.
  std::uint32_t EdgeVertex(const VoxelIndex& v, int a, int b, const float distances[8]) {
    const VoxelIndex low = v + VoxelIndex(a & 1, (a >> 1) & 1, (a >> 2) & 1);
    std::uint64_t key = 0;
    for (int axis = 0; axis < 3; ++axis) {
      key = (key << kPackBits) |
            (static_cast<std::uint64_t>(low[axis] + kPackOffset) & ((1u << kPackBits) - 1));
    }
    key = (key << 3) | static_cast<std::uint64_t>(b & ~a);
    const auto [it, added] =
        vertex_of_edge_.try_emplace(key, static_cast<std::uint32_t>(mesh_.positions.size()));
    if (added) {
      const VoxelIndex high = v + VoxelIndex(b & 1, (b >> 1) & 1, (b >> 2) & 1);
      const float t = distances[a] / (distances[a] - distances[b]);
      const Eigen::Vector3f pa = volume_.Position(low);
      mesh_.positions.push_back(pa + t * (volume_.Position(high) - pa));
    }
    return it->second;
  }

  // Adds triangle (a, b, c), turned to face `outward`, unless it has no area.
  void AddTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                   const Eigen::Vector3f& outward) {
    if (a == b || b == c || a == c) return;
    const Eigen::Vector3f& pa = mesh_.positions[a];
    const Eigen::Vector3f normal =
        (mesh_.positions[b] - pa).cross(mesh_.positions[c] - pa);
    if (!(normal.squaredNorm() > 0)) return;
    if (normal.dot(outward) < 0) std::swap(b, c);
    mesh_.triangles.emplace_back(a, b, c);
  }

  void AddTetrahedron(const VoxelIndex& v, const std::array<int, 4>& tet,
                      const float distances[8]) {
    std::array<int, 4> inside{}, outside{};
    int inside_count = 0, outside_count = 0;
    for (int corner : tet) {
      if (distances[corner] < 0) {
        inside[inside_count++] = corner;
      } else {
        outside[outside_count++] = corner;
      }
    }
    if (inside_count == 0 || outside_count == 0) return;
    auto corner_position = [&](int c) {
      return volume_.Position(v + VoxelIndex(c & 1, (c >> 1) & 1, (c >> 2) & 1));
    };
    Eigen::Vector3f inside_centre = Eigen::Vector3f::Zero(), outside_centre = inside_centre;
    for (int i = 0; i < inside_count; ++i) inside_centre += corner_position(inside[i]);
    for (int i = 0; i < outside_count; ++i) outside_centre += corner_position(outside[i]);
    const Eigen::Vector3f outward = outside_centre / static_cast<float>(outside_count) -
                                    inside_centre / static_cast<float>(inside_count);
    // An edge's vertex, named by its two corners in either order.
    auto vertex = [&](int p, int q) {
      return (p & q) == p ? EdgeVertex(v, p, q, distances) : EdgeVertex(v, q, p, distances);
    };
    if (inside_count == 2) {
      const int a = inside[0], b = inside[1], c = outside[0], d = outside[1];
      const std::uint32_t ac = vertex(a, c), ad = vertex(a, d), bd = vertex(b, d),
                          bc = vertex(b, c);
      AddTriangle(ac, ad, bd, outward);
      AddTriangle(ac, bd, bc, outward);
      return;
    }
    const bool lone_inside = inside_count == 1;
    const int lone = lone_inside ? inside[0] : outside[0];
    const std::array<int, 4>& others = lone_inside ? outside : inside;
    AddTriangle(vertex(lone, others[0]), vertex(lone, others[1]), vertex(lone, others[2]),
                outward);
  }

  const DistanceVolume& volume_;
  TriangleMesh mesh_;
  std::unordered_map<std::uint64_t, std::uint32_t> vertex_of_edge_;
};

}  // namespace

TriangleMesh ContourDistanceVolume(const DistanceVolume& volume) {
  TetrahedraMesher mesher(volume);
  float distances[8];
  volume.ForEachVoxel([&](const VoxelIndex& v) {
    if (!volume.CubeDistances(v, distances)) return;
    bool negative = false, positive = false;
    for (float d : distances) (d < 0 ? negative : positive) = true;
    if (negative && positive) mesher.AddCube(v, distances);
  });
  return mesher.Take();
}

}  // namespace meshvid
