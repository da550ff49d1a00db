// Tests of Status/StatusOr and the shared mesh helpers.
#include <gtest/gtest.h>

#include "codec/common/mesh.h"
#include "format/status.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

StatusOr<int> Half(int x) {
  if (x % 2 != 0) return InvalidArgumentError(std::to_string(x) + " is odd");
  return x / 2;
}

Status QuarterInto(int x, int* out) {
  MESHVID_ASSIGN_OR_RETURN(const int half, Half(x));
  MESHVID_ASSIGN_OR_RETURN(*out, Half(half));
  return Status::Ok();
}

TEST(StatusTest, ErrorsPropagateWithTheirMessage) {
  int out = 0;
  EXPECT_TRUE(QuarterInto(8, &out).ok());
  EXPECT_EQ(out, 2);
  const Status s = QuarterInto(6, &out);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.ToString(), "invalid argument: 3 is odd");
  EXPECT_EQ(s.WithContext("f.ply").message(), "f.ply: 3 is odd");
}

TEST(MeshTest, ValidateNamesTheProblem) {
  TriangleMesh mesh = testing::MakeGridPlane(1.0f, 2);
  EXPECT_TRUE(ValidateMesh(mesh, "plane").ok());
  mesh.positions[3].y() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(ValidateMesh(mesh, "plane").message(),
            "plane: vertex 3 has a NaN or infinite coordinate");
  mesh = testing::MakeGridPlane(1.0f, 2);
  mesh.triangles[1][2] = 9;
  EXPECT_EQ(ValidateMesh(mesh, "plane").message(),
            "plane: triangle 1 uses vertex index 9 but there are only 9 vertices");
  EXPECT_EQ(ValidateMesh(TriangleMesh{}, "x").message(), "x: mesh has no vertices");
}

TEST(MeshTest, AreaNormalsAndAppend) {
  TriangleMesh mesh = testing::MakeGridPlane(2.0f, 4);
  EXPECT_NEAR(SurfaceArea(mesh), 4.0, 1e-6);
  for (const auto& n : ComputeVertexNormals(mesh)) EXPECT_NEAR(n.z(), 1.0f, 1e-6f);
  TriangleMesh both = mesh;
  AppendMesh(mesh, &both);
  EXPECT_EQ(both.vertex_count(), 2 * mesh.vertex_count());
  EXPECT_EQ(both.triangles.back(), Triangle(mesh.triangles.back().array() + 25u));
  EXPECT_NEAR(SurfaceArea(both), 8.0, 1e-6);
}

TEST(MeshTest, ViewsHaveColourOnlyWhenEveryViewWithASurfaceHasAColourPerVertex) {
  TriangleMesh coloured = testing::MakeGridPlane(1.0f, 2);
  coloured.colours.assign(coloured.vertex_count(), Colour(1, 2, 3));
  const TriangleMesh plain = testing::MakeGridPlane(1.0f, 2);
  TriangleMesh short_of_colours = coloured;
  short_of_colours.colours.pop_back();
  const TriangleMesh nothing_seen;  // a view that saw nothing has no colours and needs none
  EXPECT_TRUE(ViewsHaveColour(std::vector<TriangleMesh>{coloured, nothing_seen}));
  EXPECT_FALSE(ViewsHaveColour(std::vector<TriangleMesh>{coloured, plain}));
  EXPECT_FALSE(ViewsHaveColour(std::vector<TriangleMesh>{coloured, short_of_colours}));
  EXPECT_FALSE(ViewsHaveColour(std::vector<TriangleMesh>{plain, nothing_seen}));
  EXPECT_FALSE(ViewsHaveColour(std::vector<TriangleMesh>{}));
}

TEST(MeshTest, RemoveUnreferencedVerticesRenumbers) {
  TriangleMesh mesh;
  mesh.positions = {{9, 9, 9}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {Triangle(1, 2, 3)};
  RemoveUnreferencedVertices(&mesh);
  ASSERT_EQ(mesh.vertex_count(), 3u);
  EXPECT_EQ(mesh.triangles[0], Triangle(0, 1, 2));
  EXPECT_EQ(mesh.positions[0], Eigen::Vector3f(0, 0, 0));
}

TEST(MeshTest, SplitNonManifoldVerticesGivesEachFanItsVertex) {
  // Two fans of two triangles each meet at vertex 0 only (a bow tie of quads).
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                    {-1, 0, 0}, {-1, -1, 0}, {0, -1, 0}};
  mesh.triangles = {Triangle(0, 1, 2), Triangle(0, 2, 3), Triangle(0, 4, 5), Triangle(0, 5, 6)};
  const double area = SurfaceArea(mesh);
  EXPECT_EQ(SplitNonManifoldVertices(&mesh), 1u);
  ASSERT_EQ(mesh.vertex_count(), 8u);
  EXPECT_EQ(mesh.positions[7], mesh.positions[0]);
  // The first fan keeps vertex 0; the second uses the copy throughout.
  EXPECT_EQ(mesh.triangles[0][0], 0u);
  EXPECT_EQ(mesh.triangles[1][0], 0u);
  EXPECT_EQ(mesh.triangles[2][0], 7u);
  EXPECT_EQ(mesh.triangles[3][0], 7u);
  EXPECT_DOUBLE_EQ(SurfaceArea(mesh), area);
  // A manifold mesh (a closed octahedron, an open grid) is left alone.
  TriangleMesh octahedron;
  octahedron.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  octahedron.triangles = {Triangle(0, 2, 4), Triangle(2, 1, 4), Triangle(1, 3, 4),
                          Triangle(3, 0, 4), Triangle(2, 0, 5), Triangle(1, 2, 5),
                          Triangle(3, 1, 5), Triangle(0, 3, 5)};
  const TriangleMesh before = octahedron;
  EXPECT_EQ(SplitNonManifoldVertices(&octahedron), 0u);
  EXPECT_EQ(octahedron.triangles, before.triangles);
  TriangleMesh grid = testing::MakeGridPlane(1.0f, 6);
  EXPECT_EQ(SplitNonManifoldVertices(&grid), 0u);
}

}  // namespace
}  // namespace meshvid
