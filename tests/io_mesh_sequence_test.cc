// Tests of OpenMeshSequence: OBJ + PC2, folders, patterns, single files, shared data.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/test_util.h"
#include "tools/io/mesh_io.h"
#include "tools/io/mesh_sequence.h"
#include "tools/io/pc2.h"

namespace meshvid {
namespace {

using testing::MakeGridPlane;
using testing::TempDir;
using testing::WriteFile;

void WritePlane(const std::string& path, int n) {
  ASSERT_TRUE(WriteMesh(path, MakeGridPlane(2.0f, n)).ok()) << path;
}

/// Writes NAME.obj (a 3x3-quad plane) and NAME.pc2 with `frames` frames, frame t lifted to z = t.
void WriteAnimation(const std::string& stem, int frames, int points = 16) {
  ASSERT_TRUE(WriteMesh(stem + ".obj", MakeGridPlane(2.0f, 3)).ok());
  auto writer = Pc2Writer::Create(stem + ".pc2", points);
  ASSERT_TRUE(writer.ok()) << writer.status().ToString();
  const TriangleMesh plane = MakeGridPlane(2.0f, 3);
  for (int t = 0; t < frames; ++t) {
    std::vector<Eigen::Vector3f> positions(points, Eigen::Vector3f::Zero());
    for (int i = 0; i < points && i < 16; ++i) {
      positions[i] = plane.positions[i] + Eigen::Vector3f(0, 0, static_cast<float>(t));
    }
    ASSERT_TRUE((*writer)->AppendFrame(positions).ok());
  }
  ASSERT_TRUE((*writer)->Finish().ok());
}

TEST(MeshSequenceTest, ObjWithPc2IsAnAnimationOfTheTemplate) {
  TempDir dir;
  WriteAnimation(dir.File("wave"), 4);
  for (const std::string& spec : {dir.File("wave.obj"), dir.File("wave.pc2")}) {
    auto sequence = OpenMeshSequence(spec, 30.0);
    ASSERT_TRUE(sequence.ok()) << sequence.status().ToString();
    EXPECT_EQ((*sequence)->frame_count(), 4);
    EXPECT_EQ((*sequence)->frame_rate(), 30.0);
    EXPECT_TRUE((*sequence)->fixed_connectivity());
    EXPECT_NE((*sequence)->description().find("wave.pc2"), std::string::npos);
    const auto frame = (*sequence)->Frame(2);
    ASSERT_TRUE(frame.ok()) << frame.status().ToString();
    const TriangleMesh plane = MakeGridPlane(2.0f, 3);
    ASSERT_EQ(frame->vertex_count(), 16u);
    EXPECT_EQ(frame->triangles, plane.triangles);
    for (size_t i = 0; i < 16; ++i) {
      EXPECT_EQ(frame->positions[i], plane.positions[i] + Eigen::Vector3f(0, 0, 2));
    }
    EXPECT_EQ((*sequence)->Frame(4).status().code(), StatusCode::kInvalidArgument);
    EXPECT_EQ((*sequence)->Frame(-1).status().code(), StatusCode::kInvalidArgument);
  }
}

TEST(MeshSequenceTest, Pc2PointCountMustMatchTheObj) {
  TempDir dir;
  WriteAnimation(dir.File("bad"), 2, 17);
  const auto sequence = OpenMeshSequence(dir.File("bad.obj"));
  ASSERT_FALSE(sequence.ok());
  EXPECT_EQ(sequence.status().message(), dir.File("bad.pc2") + " has 17 points per frame but " +
                                             dir.File("bad.obj") +
                                             " has 16 vertices; they must be the same animation");
}

TEST(MeshSequenceTest, FolderIsReadInNameOrder) {
  TempDir dir;
  WritePlane(dir.File("b.ply"), 1);
  WritePlane(dir.File("a.obj"), 2);
  WritePlane(dir.File("c.PLY"), 3);
  WriteFile(dir.File("notes.txt"), "not a mesh");
  auto sequence = OpenMeshSequence(dir.path(), 24.0);
  ASSERT_TRUE(sequence.ok()) << sequence.status().ToString();
  ASSERT_EQ((*sequence)->frame_count(), 3);
  EXPECT_EQ((*sequence)->frame_rate(), 24.0);
  EXPECT_FALSE((*sequence)->fixed_connectivity());
  EXPECT_EQ((*sequence)->Frame(0)->vertex_count(), 9u);   // a.obj
  EXPECT_EQ((*sequence)->Frame(1)->vertex_count(), 4u);   // b.ply
  EXPECT_EQ((*sequence)->Frame(2)->vertex_count(), 16u);  // c.PLY
  TempDir empty;
  EXPECT_EQ(OpenMeshSequence(empty.path()).status().code(), StatusCode::kNotFound);
}

TEST(MeshSequenceTest, PatternFramesAreContiguousFromTheSmallest) {
  TempDir dir;
  for (int f = 5; f <= 7; ++f) WritePlane(dir.File("m00" + std::to_string(f) + ".ply"), f - 4);
  auto sequence = OpenMeshSequence(dir.File("m{frame:03}.ply"));
  ASSERT_TRUE(sequence.ok()) << sequence.status().ToString();
  ASSERT_EQ((*sequence)->frame_count(), 3);
  EXPECT_EQ((*sequence)->frame_rate(), 25.0);
  EXPECT_EQ((*sequence)->Frame(0)->vertex_count(), 4u);   // m005
  EXPECT_EQ((*sequence)->Frame(2)->vertex_count(), 16u);  // m007
  WritePlane(dir.File("m009.ply"), 1);
  const auto gap = OpenMeshSequence(dir.File("m{frame:03}.ply"));
  ASSERT_FALSE(gap.ok());
  EXPECT_EQ(gap.status().message(), "pattern '" + dir.File("m{frame:03}.ply") +
                                        "': frames must be contiguous, but "
                                        "frame 8 (" +
                                        dir.File("m008.ply") + ") is missing before frame 9");
  EXPECT_EQ(OpenMeshSequence(dir.File("m{view}.ply")).status().code(),
            StatusCode::kInvalidArgument);
}

TEST(MeshSequenceTest, SingleFileIsOneFrame) {
  TempDir dir;
  WritePlane(dir.File("one.obj"), 2);
  auto sequence = OpenMeshSequence(dir.File("one.obj"));
  ASSERT_TRUE(sequence.ok()) << sequence.status().ToString();
  EXPECT_EQ((*sequence)->frame_count(), 1);
  EXPECT_TRUE((*sequence)->fixed_connectivity());
  EXPECT_EQ((*sequence)->Frame(0)->vertex_count(), 9u);
  EXPECT_EQ((*sequence)->Frame(1).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(OpenMeshSequence(dir.File("none.obj")).status().code(), StatusCode::kNotFound);
  WriteFile(dir.File("x.txt"), "x");
  EXPECT_EQ(OpenMeshSequence(dir.File("x.txt")).status().code(), StatusCode::kUnsupported);
  // A broken frame fails when it is read, naming its file.
  WriteFile(dir.File("broken.obj"), "v 0 0 0\nf 1 2 3\n");
  auto broken = OpenMeshSequence(dir.File("broken.obj"));
  ASSERT_TRUE(broken.ok());
  const auto frame = (*broken)->Frame(0);
  ASSERT_FALSE(frame.ok());
  EXPECT_NE(frame.status().message().find(dir.File("broken.obj")), std::string::npos);
}

TEST(MeshSequenceTest, SambaGroundTruthOpensLazily) {
  MESHVID_REQUIRE_SHARED_DATA();
  auto sequence = OpenMeshSequence(shared_data + "/sequences/samba.obj", 25.0);
  ASSERT_TRUE(sequence.ok()) << sequence.status().ToString();
  EXPECT_EQ((*sequence)->frame_count(), 175);
  EXPECT_TRUE((*sequence)->fixed_connectivity());
  const auto frame = (*sequence)->Frame(100);
  ASSERT_TRUE(frame.ok()) << frame.status().ToString();
  EXPECT_EQ(frame->vertex_count(), 9971u);
  const auto first = (*sequence)->Frame(0);
  ASSERT_TRUE(first.ok());
  EXPECT_EQ(first->triangles, frame->triangles);
  EXPECT_NE(first->positions, frame->positions);  // the dancer moves
}

}  // namespace
}  // namespace meshvid
