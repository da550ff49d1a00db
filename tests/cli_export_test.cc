// `meshvid export` to OBJ + PC2: the exported caches hold exactly what `meshvid decode`
// writes, one pair per key group.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/test_util.h"
#include "tools/io/mesh_io.h"
#include "tools/io/pc2.h"

namespace meshvid {
namespace {

const std::string kGoldenV1 = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v1.mvid";
// Three key groups: frames 0-4, 5-8, 9-11 (codec_mvid_test's ThreeKeyGroups).
const std::string kGoldenV2 = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v2.mvid";

/// Checks that `obj` + `pc2` hold the frames [first, end) that decode wrote to dec/fNN.ply.
void ExpectCacheEqualsDecode(const testing::TempDir& dir, const std::string& obj,
                             const std::string& pc2, int first, int end) {
  auto connectivity = ReadMesh(obj);
  ASSERT_TRUE(connectivity.ok()) << connectivity.status().message();
  auto cache = Pc2Reader::Open(pc2);
  ASSERT_TRUE(cache.ok()) << cache.status().message();
  EXPECT_EQ((*cache)->header().num_samples, end - first);
  EXPECT_EQ((*cache)->header().start_frame, static_cast<float>(first));
  for (int frame = first; frame < end; ++frame) {
    char name[32];
    std::snprintf(name, sizeof name, "dec/f%02d.ply", frame);
    auto decoded = ReadMesh(dir.File(name));
    ASSERT_TRUE(decoded.ok()) << decoded.status().message();
    EXPECT_EQ(connectivity->triangles, decoded->triangles) << "frame " << frame;
    auto positions = (*cache)->ReadFrame(frame - first);
    ASSERT_TRUE(positions.ok());
    ASSERT_EQ(positions->size(), decoded->positions.size());
    for (std::size_t i = 0; i < positions->size(); ++i) {
      // Both are the decoder's float32 positions: bit-identical.
      ASSERT_EQ((*positions)[i], decoded->positions[i]) << "frame " << frame << " vertex " << i;
    }
  }
}

TEST(ExportCliTest, MeshCachePerKeyGroupEqualsDecode) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string range = " --level 1 --frames 3:11";
  const testing::CliRun exported = testing::RunMeshvid(
      "export '" + kGoldenV2 + "' -o '" + dir.File("out/anim.obj") + "'" + range, dir);
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const testing::CliRun decoded = testing::RunMeshvid(
      "decode '" + kGoldenV2 + "' -o '" + dir.File("dec/f{frame:02}.ply") + "'" + range, dir);
  ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("out/anim.obj")));
  ExpectCacheEqualsDecode(dir, dir.File("out/anim_kg0.obj"), dir.File("out/anim_kg0.pc2"), 3, 5);
  ExpectCacheEqualsDecode(dir, dir.File("out/anim_kg1.obj"), dir.File("out/anim_kg1.pc2"), 5, 9);
  ExpectCacheEqualsDecode(dir, dir.File("out/anim_kg2.obj"), dir.File("out/anim_kg2.pc2"), 9,
                          11);
}

TEST(ExportCliTest, OneKeyGroupKeepsTheGivenName) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const testing::CliRun exported =
      testing::RunMeshvid("export -q '" + kGoldenV1 + "' -o '" + dir.File("s.obj") + "'", dir);
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const testing::CliRun decoded = testing::RunMeshvid(
      "decode -q '" + kGoldenV1 + "' -o '" + dir.File("dec/f{frame:02}.ply") + "'", dir);
  ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
  ExpectCacheEqualsDecode(dir, dir.File("s.obj"), dir.File("s.pc2"), 0, 6);
}

TEST(ExportCliTest, RejectsAnUnknownFormatAndABadLevel) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  EXPECT_EQ(testing::RunMeshvid("export '" + kGoldenV1 + "' -o '" + dir.File("x.fbx") + "'", dir)
                .exit_code,
            2);
  const testing::CliRun level = testing::RunMeshvid(
      "export '" + kGoldenV1 + "' -o '" + dir.File("x.obj") + "' --level 9", dir);
  EXPECT_EQ(level.exit_code, 1);
  EXPECT_NE(level.err.find("levels 0..2"), std::string::npos) << level.err;
}

}  // namespace
}  // namespace meshvid
