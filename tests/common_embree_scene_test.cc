// EmbreeScene: ray hits, packets, point queries, rebuilds and the shared device's lifetime.
#include "codec/common/embree_scene.h"

#include <gtest/gtest.h>

#include "tests/test_util.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace meshvid {
namespace {

/// The unit square [0,1]^2 at height z, two triangles facing +z.
TriangleMesh Square(float z) {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z}};
  mesh.triangles = {Triangle(0, 1, 2), Triangle(0, 2, 3)};
  return mesh;
}

TEST(EmbreeSceneTest, FirstHitWithinTheRayInterval) {
  auto scene = EmbreeScene::Create(Square(2.0f));
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  const RayHit hit = (*scene)->Intersect({0.25f, 0.75f, 0}, {0, 0, 1});
  ASSERT_TRUE(hit.hit());
  EXPECT_FLOAT_EQ(hit.t, 2.0f);
  EXPECT_EQ(hit.triangle, 1u);
  EXPECT_GT(hit.normal.z(), 0.0f);
  EXPECT_FALSE((*scene)->Intersect({0.25f, 0.75f, 0}, {0, 0, 1}, 0.0f, 1.5f).hit());
  EXPECT_FALSE((*scene)->Intersect({0.25f, 0.75f, 0}, {0, 0, -1}).hit());
  EXPECT_FALSE((*scene)->Intersect({2.0f, 0.5f, 0}, {0, 0, 1}).hit());
}

TEST(EmbreeSceneTest, PacketMatchesSingleRays) {
  auto scene = EmbreeScene::Create(Square(1.0f));
  ASSERT_TRUE(scene.ok());
  RayPacket packet;
  packet.count = 11;  // a partial packet
  for (int i = 0; i < packet.count; ++i) {
    packet.origin[i] = Eigen::Vector3f(-0.25f + 0.15f * i, 0.5f, 0);
    packet.direction[i] = Eigen::Vector3f(0.01f * i, 0, 1);
    packet.t_far[i] = i == 3 ? 0.5f : INFINITY;
  }
  RayHit hits[RayPacket::kSize];
  (*scene)->IntersectPacket(packet, hits);
  int hit_count = 0;
  for (int i = 0; i < packet.count; ++i) {
    const RayHit single =
        (*scene)->Intersect(packet.origin[i], packet.direction[i], 0.0f, packet.t_far[i]);
    ASSERT_EQ(hits[i].hit(), single.hit()) << "ray " << i;
    if (single.hit()) {
      EXPECT_FLOAT_EQ(hits[i].t, single.t);
      EXPECT_EQ(hits[i].triangle, single.triangle);
      ++hit_count;
    }
  }
  EXPECT_FALSE(hits[3].hit());  // cut short by its t_far
  EXPECT_GE(hit_count, 5);
}

TEST(EmbreeSceneTest, PointQueryVisitsOnlyNearTriangles) {
  TriangleMesh mesh = Square(0.0f);
  AppendMesh(testing::MakeGridPlane(1.0f, 20, 10.0f), &mesh);  // 800 triangles far away
  auto scene = EmbreeScene::Create(mesh);
  ASSERT_TRUE(scene.ok());
  std::vector<std::uint32_t> visited;
  (*scene)->VisitTrianglesNear(
      {0.5f, 0.5f, 0.1f}, 1.0f,
      [](void* user, std::uint32_t triangle, float*) {
        static_cast<std::vector<std::uint32_t>*>(user)->push_back(triangle);
        return false;
      },
      &visited);
  // Both near triangles are visited; the far plane's are pruned (bar a shared BVH leaf).
  EXPECT_NE(std::find(visited.begin(), visited.end(), 0u), visited.end());
  EXPECT_NE(std::find(visited.begin(), visited.end(), 1u), visited.end());
  EXPECT_LT(visited.size(), 40u);
}

TEST(EmbreeSceneTest, UpdateMovesTheSurface) {
  auto scene = EmbreeScene::Create(Square(1.0f));
  ASSERT_TRUE(scene.ok());
  ASSERT_TRUE((*scene)->Update(Square(3.0f)).ok());  // same sizes: buffers reused
  EXPECT_FLOAT_EQ((*scene)->Intersect({0.5f, 0.5f, 0}, {0, 0, 1}).t, 3.0f);
  TriangleMesh bigger = Square(5.0f);
  AppendMesh(Square(4.0f), &bigger);
  ASSERT_TRUE((*scene)->Update(bigger).ok());  // new sizes: rebuilt
  EXPECT_FLOAT_EQ((*scene)->Intersect({0.5f, 0.5f, 0}, {0, 0, 1}).t, 4.0f);
  EXPECT_EQ((*scene)->triangle_count(), 4u);
  EXPECT_FLOAT_EQ((*scene)->bounds().max().z(), 5.0f);
}

TEST(EmbreeSceneTest, RejectsAnEmptyMesh) {
  EXPECT_FALSE(EmbreeScene::Create(TriangleMesh{}).ok());
}

TEST(EmbreeSceneTest, ScenesWorkAfterEveryEarlierSceneIsGone) {
  // The device is released with the last scene and created again by the next.
  for (int round = 0; round < 3; ++round) {
    auto scene = EmbreeScene::Create(Square(1.0f + round));
    ASSERT_TRUE(scene.ok());
    EXPECT_FLOAT_EQ((*scene)->Intersect({0.5f, 0.5f, 0}, {0, 0, 1}).t, 1.0f + round);
  }
}

}  // namespace
}  // namespace meshvid
