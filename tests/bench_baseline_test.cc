// ColourVerticesFromViews (tools/bench/baseline.h): the per-frame baseline's vertex colours.
#include "tools/bench/baseline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/test_util.h"

namespace meshvid {
namespace {

/// The view's colour at x: a ramp of red along x, so a vertex's colour says where it was found.
Colour RampAt(float x) {
  return Colour(static_cast<std::uint8_t>(std::lround(100.0f + 100.0f * x)), 50, 200);
}

TEST(BaselineColourTest, VerticesTakeWhatTheViewSeesThereAndUnseenOnesTheirNeighbours) {
  // One view: a plane of side 2 (x in -1..1) with the ramp, its surface only where x < 0.5.
  TriangleMesh view = testing::MakeGridPlane(2.0f, 40);
  for (const Eigen::Vector3f& p : view.positions) view.colours.push_back(RampAt(p.x()));
  std::vector<Triangle> seen;
  for (const Triangle& t : view.triangles) {
    const float x =
        (view.positions[t[0]].x() + view.positions[t[1]].x() + view.positions[t[2]].x()) / 3;
    if (x < 0.5f) seen.push_back(t);
  }
  view.triangles = seen;
  // The mesh to colour: the whole plane, tessellated otherwise and 2 mm off the view's.
  TriangleMesh mesh = testing::MakeGridPlane(2.0f, 17, 0.002f);
  const std::vector<TriangleMesh> views = {view};
  ASSERT_TRUE(ColourVerticesFromViews(views, {}, &mesh).ok());
  ASSERT_EQ(mesh.colours.size(), mesh.vertex_count());
  // The seen part ends between the mesh's vertices at x 0.41 and the view's edge at 0.5.
  const int edge_red = RampAt(0.45f)[0];
  int checked_seen = 0, checked_unseen = 0;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const float x = mesh.positions[i].x();
    const Colour& c = mesh.colours[i];
    // A vertex right over the view's outer border may miss it (and be filled): left out.
    if (std::abs(mesh.positions[i].y()) > 0.95f || x < -0.95f) continue;
    if (x < 0.4f) {
      // Seen: the view's colour there (one view, so its exposure gain is 1).
      EXPECT_NEAR(c[0], RampAt(x)[0], 2) << i;
      EXPECT_EQ(c[1], 50) << i;
      EXPECT_EQ(c[2], 200) << i;
      ++checked_seen;
    } else if (x > 0.6f) {
      // Unseen: spread from the seen part's edge, not the mean of the frame, nor black.
      EXPECT_NEAR(c[0], edge_red, 8) << i;
      EXPECT_EQ(c[2], 200) << i;
      ++checked_unseen;
    }
  }
  EXPECT_GT(checked_seen, 100);
  EXPECT_GT(checked_unseen, 50);
}

TEST(BaselineColourTest, AMeshNoViewSeesTakesTheNeutralGrey) {
  TriangleMesh view = testing::MakeGridPlane(2.0f, 8);
  for (std::size_t i = 0; i < view.vertex_count(); ++i) view.colours.push_back(RampAt(0));
  TriangleMesh far_away = testing::MakeGridPlane(2.0f, 8, 1.0f);  // 1 m off: no shot reaches
  const std::vector<TriangleMesh> views = {view};
  ASSERT_TRUE(ColourVerticesFromViews(views, {}, &far_away).ok());
  for (const Colour& c : far_away.colours) EXPECT_EQ(c, Colour(128, 128, 128));
}

}  // namespace
}  // namespace meshvid
