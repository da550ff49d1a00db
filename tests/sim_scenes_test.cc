// Procedural scenes and the ground-truth opener.
#include <gtest/gtest.h>

#include <set>

#include "tools/sim/ground_truth.h"
#include "tools/sim/scenes.h"

namespace meshvid {
namespace {

void ExpectWellFormedSequence(MeshSequence& scene, std::size_t min_vertices,
                              std::size_t max_vertices) {
  EXPECT_EQ(scene.frame_count(), 100);
  EXPECT_DOUBLE_EQ(scene.frame_rate(), 25.0);
  EXPECT_TRUE(scene.fixed_connectivity());
  auto first = scene.Frame(0);
  ASSERT_TRUE(first.ok()) << first.status().ToString();
  EXPECT_GE(first->vertex_count(), min_vertices);
  EXPECT_LE(first->vertex_count(), max_vertices);
  for (int t = 0; t < scene.frame_count(); t += 9) {
    auto mesh = scene.Frame(t);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    EXPECT_TRUE(ValidateMesh(*mesh, scene.description()).ok());  // finite, indices in range
    EXPECT_EQ(mesh->vertex_count(), first->vertex_count());
    EXPECT_TRUE(mesh->triangles == first->triangles) << "frame " << t;
  }
  EXPECT_EQ(scene.Frame(100).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(scene.Frame(-1).status().code(), StatusCode::kInvalidArgument);
}

TEST(ScenesTest, ArmBlockIsAWellFormedSequence) {
  auto scene = MakeArmBlockScene();
  ExpectWellFormedSequence(*scene, 2000, 10000);
}

TEST(ScenesTest, ClothIsAWellFormedSequence) {
  auto scene = MakeClothScene();
  ExpectWellFormedSequence(*scene, 5000, 10000);
}

TEST(ScenesTest, ScenesAreDeterministicAndFrameCountIsConfigurable) {
  auto a = MakeClothScene({.frame_count = 12, .frame_rate = 30});
  auto b = MakeClothScene({.frame_count = 12, .frame_rate = 30});
  EXPECT_EQ(a->frame_count(), 12);
  EXPECT_DOUBLE_EQ(a->frame_rate(), 30.0);
  EXPECT_TRUE(a->Frame(11)->positions == b->Frame(11)->positions);
  EXPECT_FALSE(a->Frame(11)->positions == a->Frame(0)->positions);
}

TEST(ScenesTest, ArmBlockLabelsPartitionTheVertices) {
  auto mesh = MakeArmBlockScene()->Frame(0);
  ASSERT_TRUE(mesh.ok());
  const std::vector<std::string> parts = ArmBlockVertexParts();
  const std::vector<std::string> pieces = ArmBlockVertexPieces();
  ASSERT_EQ(parts.size(), mesh->vertex_count());
  ASSERT_EQ(pieces.size(), mesh->vertex_count());
  std::size_t arm = 0, block = 0;
  for (std::size_t v = 0; v < parts.size(); ++v) {
    ASSERT_TRUE(parts[v] == "arm" || parts[v] == "block") << parts[v];
    (parts[v] == "arm" ? arm : block)++;
    EXPECT_EQ(pieces[v] == "block", parts[v] == "block");
  }
  EXPECT_EQ(arm + block, mesh->vertex_count());
  EXPECT_GT(block, 500u);
  EXPECT_GT(arm, 2000u);
  EXPECT_EQ(std::set<std::string>(pieces.begin(), pieces.end()),
            (std::set<std::string>{"upper_arm", "forearm", "hand", "block"}));
  // No triangle joins the block to the arm.
  for (const Triangle& t : mesh->triangles) {
    EXPECT_EQ(parts[t[0]], parts[t[1]]);
    EXPECT_EQ(parts[t[0]], parts[t[2]]);
  }
  auto labels = SceneVertexParts("arm-block");
  ASSERT_TRUE(labels.ok());
  EXPECT_EQ(*labels, parts);
}

TEST(ScenesTest, BlockMovesRigidlyAndTheArmBends) {
  auto scene = MakeArmBlockScene();
  const std::vector<std::string> parts = ArmBlockVertexParts();
  const std::vector<std::string> pieces = ArmBlockVertexPieces();
  std::vector<std::size_t> block, arm;
  for (std::size_t v = 0; v < parts.size(); ++v) {
    if (parts[v] == "block" && block.size() < 60 && v % 7 == 0) block.push_back(v);
    if (parts[v] == "arm" && v % 53 == 0) arm.push_back(v);  // spread over the whole arm
  }
  ASSERT_EQ(block.size(), 60u);
  ASSERT_GT(arm.size(), 50u);
  auto rest = scene->Frame(0);
  ASSERT_TRUE(rest.ok());
  double block_travel = 0, arm_strain = 0;
  for (int t = 1; t < scene->frame_count(); t += 7) {
    auto mesh = scene->Frame(t);
    ASSERT_TRUE(mesh.ok());
    for (std::size_t i = 0; i < block.size(); ++i) {
      for (std::size_t j = i + 1; j < block.size(); ++j) {
        const float d0 = (rest->positions[block[i]] - rest->positions[block[j]]).norm();
        const float d1 = (mesh->positions[block[i]] - mesh->positions[block[j]]).norm();
        EXPECT_NEAR(d0, d1, 1e-5) << "frame " << t;
      }
      block_travel = std::max<double>(
          block_travel, (mesh->positions[block[i]] - rest->positions[block[i]]).norm());
    }
    for (std::size_t i = 0; i < arm.size(); ++i) {
      for (std::size_t j = i + 1; j < arm.size(); ++j) {
        const float d0 = (rest->positions[arm[i]] - rest->positions[arm[j]]).norm();
        const float d1 = (mesh->positions[arm[i]] - mesh->positions[arm[j]]).norm();
        arm_strain = std::max<double>(arm_strain, std::abs(d0 - d1));
      }
    }
  }
  EXPECT_GT(block_travel, 0.1);  // metres: the block really moves
  EXPECT_GT(arm_strain, 0.05);   // the arm as a whole is not rigid (elbow, wrist)
}

TEST(GroundTruthTest, OpensScenesAndReportsBadSpecs) {
  EXPECT_EQ(BuiltInSceneNames(), (std::vector<std::string>{"arm-block", "cloth"}));
  auto scene = OpenGroundTruth("scene:arm-block", 50.0);
  ASSERT_TRUE(scene.ok()) << scene.status().ToString();
  EXPECT_DOUBLE_EQ((*scene)->frame_rate(), 50.0);
  EXPECT_EQ((*scene)->frame_count(), 100);
  auto unknown = OpenGroundTruth("scene:teapot");
  EXPECT_EQ(unknown.status().code(), StatusCode::kNotFound);
  EXPECT_NE(unknown.status().message().find("scene:arm-block"), std::string::npos);
  auto missing = OpenGroundTruth("/no/such/dir/dancer.obj");
  EXPECT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("dancer.obj"), std::string::npos)
      << missing.status().ToString();
  EXPECT_FALSE(OpenGroundTruth("").ok());
}

}  // namespace
}  // namespace meshvid
