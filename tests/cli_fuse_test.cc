// `meshvid fuse` run as the built binary: surfaces written per frame, the JSON figures, and
// clear errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/test_util.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

TEST(FuseCliTest, FusesEveryFrameAndReportsFigures) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  testing::CliRun run = testing::RunMeshvid(
      "simulate scene:arm-block -o '" + dir.File("cap") + "' --frames 0:2 -q", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = testing::RunMeshvid("fuse '" + dir.File("cap/manifest.json") + "' -o '" +
                                dir.File("out/fused/f{frame:04}.ply") + "' --json '" +
                                dir.File("out/fuse.json") + "' -q",
                            dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("0 failed"), std::string::npos) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(testing::ReadFile(dir.File("out/fuse.json")));
  EXPECT_EQ(summary["failures"], 0);
  ASSERT_EQ(summary["frames"].size(), 2u);
  EXPECT_GT(summary["peak_memory_mb"].get<double>(), 0);
  for (int frame = 0; frame < 2; ++frame) {
    const nlohmann::json& entry = summary["frames"][frame];
    EXPECT_EQ(entry["frame"], frame);
    auto mesh = ReadMesh(dir.File("out/fused/f000" + std::to_string(frame) + ".ply"));
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    EXPECT_EQ(entry["vertices"].get<std::size_t>(), mesh->vertex_count());
    EXPECT_GT(mesh->triangle_count(), 1000u);
  }
  // Several frames into one file name: refused before any work.
  run = testing::RunMeshvid(
      "fuse '" + dir.File("cap/manifest.json") + "' -o '" + dir.File("one.ply") + "' -q", dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("{frame}"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("one.ply")));
  run = testing::RunMeshvid("fuse '" + dir.File("nope.json") + "' -q", dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("nope.json"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace meshvid
