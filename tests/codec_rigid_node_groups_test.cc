#include "codec/enc/tracking/rigid_node_groups.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

namespace meshvid {
namespace {

/// A row of `nodes` nodes along x, each moving a 3 x 3 patch of vertices (weight 1), each node
/// held to the next.
struct Row {
  std::vector<Eigen::Vector3f> rest;
  MotionModel motion;
  std::vector<std::vector<std::int32_t>> adjacent;
};

Row MakeRow(int nodes) {
  Row row;
  for (int j = 0; j < nodes; ++j) {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        row.rest.emplace_back(0.1f * float(j) + 0.03f * float(a), 0.03f * float(b),
                              0.01f * float(a * b));
        VertexBlend blend;
        blend.count = 1;
        blend.influences[0] = {static_cast<std::uint32_t>(j), 1.0f};
        row.motion.blends.push_back(blend);
      }
    }
    row.adjacent.emplace_back();
    if (j > 0) row.adjacent.back().push_back(j - 1);
    if (j + 1 < nodes) row.adjacent.back().push_back(j + 1);
  }
  row.motion.segment_count = static_cast<std::uint32_t>(nodes);
  return row;
}

RigidTransform Turn(float angle, const Eigen::Vector3f& axis, const Eigen::Vector3f& shift) {
  RigidTransform t;
  t.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(angle, axis.normalized()));
  t.translation = shift;
  return t;
}

/// Frames in which nodes [0, split) move with one rigid motion and [split, nodes) with
/// another; node `odd` (if >= 0) drifts from it along z, by `odd_shift` at the last frame.
std::vector<std::vector<RigidTransform>> TwoBodies(int nodes, int split, int frames, int odd,
                                                   float odd_shift) {
  std::vector<std::vector<RigidTransform>> tracks(frames,
                                                  std::vector<RigidTransform>(nodes));
  for (int f = 0; f < frames; ++f) {
    const RigidTransform first =
        Turn(0.1f * float(f), Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(0.02f * float(f), 0, 0));
    const RigidTransform second = Turn(-0.2f * float(f), Eigen::Vector3f(1, 1, 0),
                                       Eigen::Vector3f(0, 0.03f * float(f), 0.01f));
    for (int j = 0; j < nodes; ++j) tracks[f][j] = j < split ? first : second;
  }
  for (int f = 1; odd >= 0 && f < frames; ++f) {
    tracks[f][odd].translation.z() += odd_shift * float(f) / float(frames - 1);
  }
  return tracks;
}

TEST(RigidNodeGroups, NodesOfTwoRigidBodiesFormTwoGroups) {
  const Row row = MakeRow(10);
  const auto tracks = TwoBodies(10, 4, 5, -1, 0);
  const RigidNodeGroups groups =
      FindRigidNodeGroups(row.rest, row.motion, row.adjacent, tracks, 0.001f);
  ASSERT_EQ(groups.group_count, 2);
  for (int j = 0; j < 10; ++j) {
    EXPECT_EQ(groups.group_of_node[j], groups.group_of_node[j < 4 ? 0 : 9]) << j;
  }
  EXPECT_NE(groups.group_of_node[0], groups.group_of_node[9]);
}

TEST(RigidNodeGroups, ANodeThatMovesApartBeyondTheToleranceStaysAlone) {
  const Row row = MakeRow(10);
  // Node 7 drifts off the second body, 5 mm by the last frame: within a 1 cm tolerance it
  // joins, within 1 mm it does not.
  const auto tracks = TwoBodies(10, 4, 5, 7, 0.005f);
  RigidNodeGroups groups = FindRigidNodeGroups(row.rest, row.motion, row.adjacent, tracks, 0.01f);
  EXPECT_EQ(groups.group_count, 2);
  groups = FindRigidNodeGroups(row.rest, row.motion, row.adjacent, tracks, 0.001f);
  // Node 7 alone splits the second body's row in two: 0-3, 4-6, 7, 8-9.
  EXPECT_EQ(groups.group_count, 4);
  EXPECT_NE(groups.group_of_node[7], groups.group_of_node[6]);
  EXPECT_NE(groups.group_of_node[7], groups.group_of_node[8]);
}

TEST(RigidNodeGroups, NodesNotHeldTogetherAreNotJoined) {
  Row row = MakeRow(6);
  for (auto& list : row.adjacent) list.clear();
  const auto tracks = TwoBodies(6, 3, 4, -1, 0);
  const RigidNodeGroups groups =
      FindRigidNodeGroups(row.rest, row.motion, row.adjacent, tracks, 0.01f);
  EXPECT_EQ(groups.group_count, 6);
}

TEST(RigidNodeGroups, AGroupCarriesTheRigidTransformThatBestFitsItsVertices) {
  const Row row = MakeRow(10);
  // Node 7 drifts 0.5 mm off by the last frame: the group's transform moves it back, and the
  // group's vertices end within a fraction of that of where the exact motion puts them.
  const auto tracked = TwoBodies(10, 4, 5, 7, 0.0005f);
  const RigidNodeGroups groups =
      FindRigidNodeGroups(row.rest, row.motion, row.adjacent, tracked, 0.001f);
  ASSERT_EQ(groups.group_count, 2);
  auto tracks = tracked;
  ApplyRigidNodeGroups(groups, &tracks);
  const auto exact = TwoBodies(10, 4, 5, -1, 0);
  for (std::size_t f = 0; f < tracks.size(); ++f) {
    for (int j = 0; j < 10; ++j) {
      const RigidTransform& first = tracks[f][j < 4 ? 0 : 9];
      EXPECT_TRUE(tracks[f][j].rotation.coeffs() == first.rotation.coeffs() &&
                  tracks[f][j].translation == first.translation)
          << "frame " << f << " node " << j << " does not carry its group's transform";
      for (std::size_t v = 9 * j; v < 9 * std::size_t(j) + 9; ++v) {
        const Eigen::Vector3f& p = row.rest[v];
        const float off = (tracks[f][j].Apply(p) - exact[f][j].Apply(p)).norm();
        // The one odd node of six pulls the fit by about a sixth of its 0.5 mm.
        EXPECT_LT(off, 0.0002f) << "frame " << f << " vertex " << v;
      }
    }
  }
}

TEST(RigidNodeGroups, WithoutFramesOrNodesEveryNodeIsItsOwnGroup) {
  const Row row = MakeRow(3);
  RigidNodeGroups groups = FindRigidNodeGroups(row.rest, row.motion, row.adjacent, {}, 0.01f);
  EXPECT_EQ(groups.group_count, 3);
  MotionModel empty;
  groups = FindRigidNodeGroups({}, empty, {}, TwoBodies(1, 1, 2, -1, 0), 0.01f);
  EXPECT_EQ(groups.group_count, 0);
}

}  // namespace
}  // namespace meshvid
