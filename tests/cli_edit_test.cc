// `meshvid edit`, run as the built binary: a frame decoded to PLY, sculpted, and edited back
// moves that frame's key group only, passes `info --check`, and a mesh that is not the frame
// is refused with an error that says how to write the right one.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "codec/dec/mvid_decoder.h"
#include "tests/test_util.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

/// FFV1, 12 frames in 3 key groups.
const std::string kThreeKeyGroups = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v2.mvid";

TEST(EditCliTest, ASculptedFrameMovesItsKeyGroupOnly) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const testing::CliRun decode =
      testing::RunMeshvid("decode '" + kThreeKeyGroups + "' --frames 1:2 --level 1 -o '" +
                              dir.File("f{frame:04}.ply") + "'",
                          dir);
  ASSERT_EQ(decode.exit_code, 0) << decode.err;
  StatusOr<TriangleMesh> frame = ReadMesh(dir.File("f0001.ply"));
  ASSERT_TRUE(frame.ok()) << frame.status().ToString();
  frame->positions[7] *= 1.05f;  // out along the sphere's radius
  ASSERT_TRUE(WriteMesh(dir.File("sculpted.ply"), *frame).ok());

  const std::string out = dir.File("edited.mvid");
  const testing::CliRun run =
      testing::RunMeshvid("edit '" + kThreeKeyGroups + "' --frame 1 --level 1 --edited '" +
                              dir.File("sculpted.ply") + "' -o '" + out + "'",
                          dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("1 vertices moved"), std::string::npos) << run.err;
  const testing::CliRun check = testing::RunMeshvid("info --check '" + out + "'", dir);
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;

  auto before = MvidDecoder::OpenFile(kThreeKeyGroups);
  auto after = MvidDecoder::OpenFile(out);
  ASSERT_TRUE(before.ok() && after.ok());
  const std::uint32_t key_group = *(*before)->KeyGroupOf(1);
  for (std::uint32_t f = 0; f < (*before)->info().frame_count; ++f) {
    std::vector<float> a, b;
    ASSERT_TRUE((*before)->DecodeDisplacements(f, &a).ok());
    ASSERT_TRUE((*after)->DecodeDisplacements(f, &b).ok());
    if (*(*before)->KeyGroupOf(f) == key_group) {
      EXPECT_GT(b[7] - a[7], 0.0f) << "frame " << f;
    } else {
      EXPECT_EQ(a, b) << "frame " << f;
    }
  }
}

TEST(EditCliTest, AMeshThatIsNotTheFrameIsRefused) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const testing::CliRun decode =
      testing::RunMeshvid("decode '" + kThreeKeyGroups + "' --frames 1:2 --level 0 -o '" +
                              dir.File("f{frame:04}.ply") + "'",
                          dir);
  ASSERT_EQ(decode.exit_code, 0) << decode.err;
  const testing::CliRun run =
      testing::RunMeshvid("edit '" + kThreeKeyGroups + "' --frame 1 --level 1 --edited '" +
                              dir.File("f0001.ply") + "' -o '" + dir.File("edited.mvid") + "'",
                          dir);
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("not those of frame 1 at level 1"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("meshvid decode"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("edited.mvid")));
}

}  // namespace
}  // namespace meshvid
