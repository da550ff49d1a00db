// OBJ reading and writing, ReadMesh/WriteMesh dispatch, and the shared real data (Stanford
// bunny range scan, samba template).
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_util.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << (text) << "\n  lacks: " << (part)

StatusOr<TriangleMesh> ParseObjString(const std::string& text) {
  std::istringstream in(text);
  return ReadObj(in, "test.obj");
}

void ExpectError(const StatusOr<TriangleMesh>& result, const std::string& problem) {
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kCorrupt) << result.status().ToString();
  EXPECT_EQ(result.status().message().rfind("test.obj: ", 0), 0u) << result.status().message();
  EXPECT_CONTAINS(result.status().message(), problem);
}

TriangleMesh MakeMesh() {
  TriangleMesh mesh;
  mesh.positions = {{0.1f, 0.2f, 1.0f / 3.0f}, {1e-8f, -12345.6789f, 2}, {3, 4, 5}, {-0.5f, 0.25f, 7}};
  mesh.triangles = {Triangle(0, 1, 2), Triangle(2, 1, 3)};
  mesh.normals = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0.6f, 0.8f, 0}};
  return mesh;
}

TEST(ObjTest, RoundTripIsExactWithAndWithoutNormals) {
  const TriangleMesh mesh = MakeMesh();
  for (const bool normals : {true, false}) {
    std::ostringstream out;
    MeshWriteOptions options;
    options.write_normals = normals;
    ASSERT_TRUE(WriteObj(out, mesh, options).ok());
    const auto read = ParseObjString(out.str());
    ASSERT_TRUE(read.ok()) << read.status().ToString();
    EXPECT_EQ(read->positions, mesh.positions);
    ASSERT_EQ(read->triangles.size(), mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      EXPECT_EQ(read->triangles[t], mesh.triangles[t]);
    }
    if (normals) {
      EXPECT_EQ(read->normals, mesh.normals);
    } else {
      EXPECT_TRUE(read->normals.empty());
    }
  }
}

TEST(ObjTest, CornerFormsNegativeIndicesAndIgnoredStatements) {
  const std::string text =
      "# comment\r\nmtllib a.mtl\no thing\ng group\ns 1\nusemtl red\n\n"
      "v 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5\nv 0 1 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\n"
      "vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 -1\n"
      "f 1/1/1 2/2/2 3/3/3 4/1/4\n"  // quad -> (0,1,2), (0,2,3)
      "f -4//1 -2//3 -1//4\r\n"      // relative to 4 vertices -> (0,2,3)
      "f 2/1 3/2 4/3   # trailing comment\n"
      "l 1 2\n";
  const auto read = ParseObjString(text);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ASSERT_EQ(read->positions.size(), 4u);
  EXPECT_EQ(read->positions[1], Eigen::Vector3f(1, 0, 0));
  const std::vector<Triangle> expected = {Triangle(0, 1, 2), Triangle(0, 2, 3), Triangle(0, 2, 3),
                                          Triangle(1, 2, 3)};
  ASSERT_EQ(read->triangles.size(), expected.size());
  for (std::size_t t = 0; t < expected.size(); ++t) EXPECT_EQ(read->triangles[t], expected[t]);
  // Some corners have no normal (the v/vt face), so the normals are dropped.
  EXPECT_TRUE(read->normals.empty());
}

TEST(ObjTest, NormalsKeptOnlyWhenOnePerVertexAndConsistent) {
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 0\nvn 1 0 0\n";
  // Permuted but consistent mapping: vertex 1 -> vn 3, vertex 2 -> vn 2, vertex 3 -> vn 1.
  auto read = ParseObjString(vertices + "f 1//3 2//2 3//1\n");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ASSERT_EQ(read->normals.size(), 3u);
  EXPECT_EQ(read->normals[0], Eigen::Vector3f(1, 0, 0));
  EXPECT_EQ(read->normals[2], Eigen::Vector3f(0, 0, 1));
  // Vertex 1 uses two different normals: dropped.
  read = ParseObjString(vertices + "f 1//1 2//2 3//3\nf 1//2 3//3 2//2\n");
  ASSERT_TRUE(read.ok());
  EXPECT_TRUE(read->normals.empty());
  // Fewer normals than vertices: dropped.
  read = ParseObjString("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
  ASSERT_TRUE(read.ok());
  EXPECT_TRUE(read->normals.empty());
  // One per vertex and faces naming none: taken in order.
  read = ParseObjString(vertices + "f 1 2 3\n");
  ASSERT_TRUE(read.ok());
  ASSERT_EQ(read->normals.size(), 3u);
  EXPECT_EQ(read->normals[1], Eigen::Vector3f(0, 1, 0));
}

TEST(ObjTest, ErrorsNameTheLine) {
  ExpectError(ParseObjString("v 0 0 0\nv 1 0\n"), "line 2: 'v' needs three numbers");
  ExpectError(ParseObjString("v 0 0 0\nv 1 0 0\nv 1 inf 0\n"), "line 3: NaN or infinite value");
  ExpectError(ParseObjString("v 0 0 0\nv 1 0 0\nv 1 1 0\n\nf 1 2 4\n"),
              "line 5: vertex index 4 out of range (the file has 3 vertices)");
  ExpectError(ParseObjString("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 0\n"),
              "line 4: invalid vertex index '0'");
  ExpectError(ParseObjString("v 0 0 0\nv 1 0 0\nv 1 1 0\nf -1 -2 -4\n"),
              "line 4: invalid vertex index '-4' (there are 3 vertices so far)");
  ExpectError(ParseObjString("v 0 0 0\nv 1 0 0\nf 1 2\n"),
              "line 3: face with 2 vertices; a face needs at least 3");
  ExpectError(ParseObjString("v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n"),
              "line 5: normal index 2 out of range");
  ExpectError(ParseObjString("# nothing\n"), "OBJ has no vertices");
  ExpectError(ParseObjString("v 0 0 0\n"), "OBJ has no faces");
}

TEST(MeshIoTest, DispatchByExtension) {
  testing::TempDir dir;
  const TriangleMesh mesh = MakeMesh();
  ASSERT_TRUE(WriteMesh(dir.File("m.Obj"), mesh).ok());
  EXPECT_EQ(testing::ReadFile(dir.File("m.Obj")).rfind("# written by meshvid\nv ", 0), 0u);
  const auto read = ReadMesh(dir.File("m.Obj"));
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->positions, mesh.positions);
  EXPECT_EQ(read->normals, mesh.normals);

  testing::WriteFile(dir.File("m.txt"), "v 0 0 0\n");
  const auto unknown = ReadMesh(dir.File("m.txt"));
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.status().code(), StatusCode::kUnsupported);
  EXPECT_CONTAINS(unknown.status().message(), dir.File("m.txt") + ": unknown mesh file extension");

  const auto missing = ReadMesh(dir.File("none.obj"));
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(missing.status().message(), dir.File("none.obj") + ": no such file");

  // Missing folders are created; a parent that is a file is a clear error.
  ASSERT_TRUE(WriteMesh(dir.File("missing/dir/m.ply"), mesh).ok());
  EXPECT_TRUE(ReadMesh(dir.File("missing/dir/m.ply")).ok());
  testing::WriteFile(dir.File("blocker"), "a file, not a folder");
  const Status no_dir = WriteMesh(dir.File("blocker/m.ply"), mesh);
  EXPECT_EQ(no_dir.code(), StatusCode::kIoError);
  EXPECT_CONTAINS(no_dir.message(), dir.File("blocker/m.ply") + ": cannot create the folder");

  testing::WriteFile(dir.File("bad.ply"), "ply\nformat ascii 1.0\nend_header\n");
  const auto bad = ReadMesh(dir.File("bad.ply"));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), dir.File("bad.ply") + ": PLY has no 'vertex' element");
}

TEST(SharedDataTest, BunnyRangeScanIsMeshedFacingTheScanner) {
  MESHVID_REQUIRE_SHARED_DATA();
  const auto mesh = ReadMesh(shared_data + "/bunny-range/bun000.ply");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  // 40256 samples; those in no kept triangle (isolated or only across a jump) are dropped.
  EXPECT_GT(mesh->vertex_count(), 40000u);
  EXPECT_LE(mesh->vertex_count(), 40256u);
  // Two triangles per full grid cell, minus those cut at silhouettes: 78471 measured.
  EXPECT_GT(mesh->triangle_count(), 77000u);
  EXPECT_LT(mesh->triangle_count(), 79000u);
  double mean_z = 0;
  float longest_edge = 0;
  for (std::size_t t = 0; t < mesh->triangle_count(); ++t) {
    mean_z += TriangleNormal(*mesh, t).z();
    const Triangle& tri = mesh->triangles[t];
    for (int k = 0; k < 3; ++k) {
      longest_edge = std::max(
          longest_edge, (mesh->positions[tri[k]] - mesh->positions[tri[(k + 1) % 3]]).norm());
    }
  }
  mean_z /= static_cast<double>(mesh->triangle_count());
  EXPECT_GT(mean_z, 0.6);  // the scanner looks along -z: normals point to +z
  EXPECT_LT(longest_edge, 0.007f);  // no silhouette bridges (33 mm without the jump rule)
  const Eigen::AlignedBox3f box = BoundingBox(*mesh);
  EXPECT_NEAR(box.sizes().y(), 0.15f, 0.02f);  // the bunny is ~15 cm tall
}

TEST(SharedDataTest, SambaTemplate) {
  MESHVID_REQUIRE_SHARED_DATA();
  const auto mesh = ReadMesh(shared_data + "/sequences/samba.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->vertex_count(), 9971u);
  EXPECT_EQ(mesh->triangle_count(), 19938u);
  EXPECT_EQ(mesh->positions[0], Eigen::Vector3f(0.493530f, 0.041538f, 0.098434f));
  EXPECT_EQ(mesh->triangles[0], Triangle(17, 9609, 9592));
}

}  // namespace
}  // namespace meshvid
