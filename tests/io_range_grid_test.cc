// TriangulateRangeGrid: cells, holes, depth jumps, diagonal choice and orientation.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tools/io/range_grid.h"

namespace meshvid {
namespace {

// A width x height grid seen by an OpenCV camera at the origin: sample (r, c) at
// (c, r, depth), rows going down the image (+y), all at depth `depth`.
RangeGrid MakeFlatGrid(int width, int height, float depth = 1.0f) {
  RangeGrid grid;
  grid.width = width;
  grid.height = height;
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      grid.points.emplace_back(static_cast<float>(c), static_cast<float>(r), depth);
      grid.depth.push_back(depth);
    }
  }
  return grid;
}

void SetDepth(RangeGrid* grid, int r, int c, float depth) {
  const std::size_t i = static_cast<std::size_t>(r) * grid->width + c;
  grid->depth[i] = depth;
  grid->points[i].z() = depth;
}

TEST(RangeGridTest, FullGridGivesTwoTrianglesPerCellFacingTheSensor) {
  const TriangleMesh mesh = TriangulateRangeGrid(MakeFlatGrid(4, 3));
  EXPECT_EQ(mesh.vertex_count(), 12u);
  ASSERT_EQ(mesh.triangle_count(), 12u);
  EXPECT_TRUE(ValidateMesh(mesh, "grid").ok());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    // The sensor is at the origin looking along +z: facing it means normal z = -1.
    EXPECT_FLOAT_EQ(TriangleNormal(mesh, t).z(), -1.0f) << "triangle " << t;
  }
  EXPECT_NEAR(SurfaceArea(mesh), 6.0, 1e-6);
}

TEST(RangeGridTest, HoleRemovesTheCellsAroundIt) {
  RangeGrid grid = MakeFlatGrid(4, 3);
  SetDepth(&grid, 0, 0, 0.0f);  // corner sample: one cell lost
  TriangleMesh mesh = TriangulateRangeGrid(grid);
  EXPECT_EQ(mesh.triangle_count(), 10u);
  EXPECT_EQ(mesh.vertex_count(), 11u);
  EXPECT_EQ(mesh.positions[0], Eigen::Vector3f(1, 0, 1));  // samples kept in grid order

  grid = MakeFlatGrid(4, 3);
  grid.points[5] = Eigen::Vector3f(std::numeric_limits<float>::quiet_NaN(), 0, 1);  // (1, 1)
  mesh = TriangulateRangeGrid(grid);
  EXPECT_EQ(mesh.triangle_count(), 4u);  // 4 of the 6 cells touch sample (1, 1)
  EXPECT_EQ(mesh.vertex_count(), 6u);    // columns 2 and 3 only
}

TEST(RangeGridTest, DepthJumpsAreCut) {
  RangeGrid grid = MakeFlatGrid(4, 2);
  for (int r = 0; r < 2; ++r) {
    SetDepth(&grid, r, 2, 2.0f);
    SetDepth(&grid, r, 3, 2.0f);
  }
  TriangleMesh mesh = TriangulateRangeGrid(grid);
  EXPECT_EQ(mesh.triangle_count(), 4u);  // the middle cell spans depth 1 -> 2
  EXPECT_EQ(mesh.vertex_count(), 8u);

  // A 2% step is surface, not a discontinuity, under the default 3% rule...
  grid = MakeFlatGrid(4, 2);
  SetDepth(&grid, 0, 3, 1.02f);
  SetDepth(&grid, 1, 3, 1.02f);
  EXPECT_EQ(TriangulateRangeGrid(grid).triangle_count(), 6u);
  // ...but is cut by a 1% rule.
  EXPECT_EQ(TriangulateRangeGrid(grid, {0.01f}).triangle_count(), 4u);
}

TEST(RangeGridTest, OneFarCornerKeepsTheNearTriangle) {
  RangeGrid grid = MakeFlatGrid(2, 2);
  SetDepth(&grid, 1, 1, 2.0f);  // diagonal (0,1)-(1,0) is shorter: split along it
  const TriangleMesh mesh = TriangulateRangeGrid(grid);
  ASSERT_EQ(mesh.triangle_count(), 1u);
  EXPECT_EQ(mesh.triangles[0], Triangle(0, 2, 1));
  EXPECT_EQ(mesh.vertex_count(), 3u);
}

TEST(RangeGridTest, ShorterDiagonalIsChosen) {
  RangeGrid grid = MakeFlatGrid(2, 2);
  grid.points[3] = Eigen::Vector3f(0.5f, 0.5f, 1.0f);  // (1,1) pulled towards (0,0)
  TriangleMesh mesh = TriangulateRangeGrid(grid);
  ASSERT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.triangles[0], Triangle(0, 2, 3));
  EXPECT_EQ(mesh.triangles[1], Triangle(0, 3, 1));
  grid = MakeFlatGrid(2, 2);
  grid.points[0] = Eigen::Vector3f(0.0f, 0.0f, 1.0f);
  grid.points[1] = Eigen::Vector3f(0.6f, 0.4f, 1.0f);  // (0,1) pulled towards (1,0)
  mesh = TriangulateRangeGrid(grid);
  ASSERT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.triangles[0], Triangle(0, 2, 1));
  EXPECT_EQ(mesh.triangles[1], Triangle(1, 2, 3));
}

TEST(RangeGridTest, DegenerateInputGivesAnEmptyMesh) {
  EXPECT_TRUE(TriangulateRangeGrid(MakeFlatGrid(1, 5)).empty());
  EXPECT_TRUE(TriangulateRangeGrid(RangeGrid{}).empty());
  RangeGrid mismatched = MakeFlatGrid(3, 3);
  mismatched.depth.pop_back();
  EXPECT_TRUE(TriangulateRangeGrid(mismatched).empty());
  RangeGrid invalid = MakeFlatGrid(3, 3);
  for (float& d : invalid.depth) d = -1.0f;
  const TriangleMesh mesh = TriangulateRangeGrid(invalid);
  EXPECT_EQ(mesh.vertex_count(), 0u);
  EXPECT_EQ(mesh.triangle_count(), 0u);
}

}  // namespace
}  // namespace meshvid
