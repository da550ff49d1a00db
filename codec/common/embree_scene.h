// EmbreeScene: the one wrapper of Embree 3 in meshvid. It owns a BVH over one triangle mesh
// and answers ray queries (single rays and coherent packets) and point queries (closest
// triangles). Normal shooting (encoder), the evaluation's surface distances, the capture
// simulator and `meshvid render` are built on it; no other file includes Embree's headers.
//
// Every scene holds a reference on one shared Embree device; the device is released when the
// last scene is destroyed, and created again by the next scene.
#ifndef MESHVID_CODEC_COMMON_EMBREE_SCENE_H_
#define MESHVID_CODEC_COMMON_EMBREE_SCENE_H_

#include <cstdint>
#include <limits>
#include <memory>

#include <Eigen/Core>

#include "codec/common/mesh.h"
#include "format/status.h"

namespace meshvid {

/// The first surface a ray meets.
struct RayHit {
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  float t = std::numeric_limits<float>::infinity();  ///< ray parameter of the hit
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  ///< geometric normal, not normalised
  std::uint32_t triangle = kNone;                    ///< index of the triangle hit
  float u = 0, v = 0;  ///< barycentric coordinates of the hit (of vertices 1 and 2)
  bool hit() const { return triangle != kNone; }
};

/// Up to kSize rays traced together (neighbouring pixels of one camera, say).
struct RayPacket {
  static constexpr int kSize = 16;
  int count = 0;  ///< rays in use, 0..kSize
  Eigen::Vector3f origin[kSize];
  Eigen::Vector3f direction[kSize];
  float t_far[kSize];  ///< farthest t accepted per ray
};

/// A BVH over one triangle mesh. Queries are thread-safe; Update() may not run concurrently
/// with anything else.
class EmbreeScene {
 public:
  /// Builds the BVH over `mesh` (copied). Fails on an empty mesh or an Embree error.
  static StatusOr<std::unique_ptr<EmbreeScene>> Create(const TriangleMesh& mesh);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// Replaces the mesh and rebuilds the BVH, reusing the buffers when the sizes match.
  Status Update(const TriangleMesh& mesh);

  /// The first hit of origin + t * direction with t in [t_near, t_far].
  RayHit Intersect(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                   float t_near = 0.0f,
                   float t_far = std::numeric_limits<float>::infinity()) const;

  /// The first hits of a packet of coherent rays (t from 0); `hits` has RayPacket::kSize
  /// entries, of which packet.count are written.
  void IntersectPacket(const RayPacket& packet, RayHit* hits) const;

  /// Visits every triangle whose bounds come within `*radius` of `point` (nearest-first is not
  /// promised). `visit(user, triangle, radius)` may shrink *radius to prune the rest of the
  /// search and returns whether it did.
  using TriangleVisitor = bool (*)(void* user, std::uint32_t triangle, float* radius);
  void VisitTrianglesNear(const Eigen::Vector3f& point, float radius, TriangleVisitor visit,
                          void* user) const;

  /// Bounds of the current mesh.
  const Eigen::AlignedBox3f& bounds() const { return bounds_; }
  std::size_t vertex_count() const { return vertex_count_; }
  std::size_t triangle_count() const { return triangle_count_; }

 private:
  EmbreeScene() = default;
  struct State;
  std::unique_ptr<State> state_;
  Eigen::AlignedBox3f bounds_;
  std::size_t vertex_count_ = 0;
  std::size_t triangle_count_ = 0;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_EMBREE_SCENE_H_
