// `meshvid info`, `info --check`, `decode` and `eval` on .mvid files, run as the built binary.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/test_util.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

const std::string kGolden = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v1.mvid";

TEST(MvidCliTest, InfoDescribesTheGoldenFile) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const testing::CliRun text = testing::RunMeshvid("info '" + kGolden + "'", dir);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("6 frames at 25 fps"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("ffv1 10-bit"), std::string::npos) << text.out;

  const testing::CliRun json = testing::RunMeshvid("info --json - --check '" + kGolden + "'", dir);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["frames"], 6);
  EXPECT_EQ(j["levels"], 2);
  EXPECT_EQ(j["base"]["vertices"], 18);
  EXPECT_EQ(j["segments"], 2);
  EXPECT_EQ(j["checked"], true);
  EXPECT_EQ(j["bytes"]["file"], std::filesystem::file_size(kGolden));
  EXPECT_EQ(j["vertices_per_level"], nlohmann::json({18, 66, 258}));
  EXPECT_EQ(j["metadata"]["golden"], "sphere");
}

TEST(MvidCliTest, InfoDescribesACaptureAndChecksItsFiles) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string capture = dir.File("capture");
  const testing::CliRun simulated = testing::RunMeshvid(
      "simulate scene:arm-block -o '" + capture + "' --frames 0:3 --views 2 --seed 1 -q", dir);
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;

  const testing::CliRun text = testing::RunMeshvid("info '" + capture + "/manifest.json'", dir);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("capture of 2 views x 3 frames at 25 fps"), std::string::npos)
      << text.out;
  // A folder holding a manifest is a capture too; --check loads every view file.
  const testing::CliRun json = testing::RunMeshvid("info --check --json - '" + capture + "'", dir);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["frames"], 3);
  EXPECT_EQ(j["views"].size(), 2u);
  EXPECT_EQ(j["frame_rate"], 25.0);
  EXPECT_EQ(j["checked"], true);

  // A damaged view file: info still describes the capture, --check names the file.
  const nlohmann::json manifest =
      nlohmann::json::parse(testing::ReadFile(capture + "/manifest.json"));
  const std::string damaged = manifest["frames"][2][1];
  testing::WriteFile(capture + "/" + damaged, "ply\nformat nonsense\n");
  EXPECT_EQ(testing::RunMeshvid("info '" + capture + "'", dir).exit_code, 0);
  const testing::CliRun checked = testing::RunMeshvid("info --check '" + capture + "'", dir);
  EXPECT_EQ(checked.exit_code, 1);
  EXPECT_NE(checked.err.find(damaged), std::string::npos) << checked.err;
}

TEST(MvidCliTest, CheckFindsAFlippedBit) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  std::string bytes = testing::ReadFile(kGolden);
  bytes[bytes.size() / 2] ^= 0x10;
  testing::WriteFile(dir.File("flipped.mvid"), bytes);
  const testing::CliRun run = testing::RunMeshvid("info --check '" + dir.File("flipped.mvid") + "'", dir);
  EXPECT_EQ(run.exit_code, 1);
  // The report on stdout names the bad chunk; stderr says only that the check failed.
  EXPECT_NE(run.out.find("crc BAD"), std::string::npos) << run.out << run.err;
  EXPECT_NE(run.err.find("the check failed"), std::string::npos) << run.err;
}

TEST(MvidCliTest, DecodeWritesEveryFrameWithTheSameTriangles) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const testing::CliRun run = testing::RunMeshvid(
      "decode '" + kGolden + "' -o '" + dir.File("f{frame:02}.ply") + "' --level 1 --frames 2:5",
      dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  auto first = ReadMesh(dir.File("f02.ply"));
  auto last = ReadMesh(dir.File("f04.ply"));
  ASSERT_TRUE(first.ok() && last.ok());
  EXPECT_FALSE(std::filesystem::exists(dir.File("f05.ply")));
  EXPECT_FALSE(std::filesystem::exists(dir.File("f01.ply")));
  EXPECT_EQ(first->vertex_count(), 66u);
  EXPECT_EQ(first->triangle_count(), 128u);
  EXPECT_EQ(first->triangles, last->triangles);
  EXPECT_NE(first->positions, last->positions);

  const testing::CliRun bad_level =
      testing::RunMeshvid("decode '" + kGolden + "' -o '" + dir.File("x{frame}.obj") + "' --level 3", dir);
  EXPECT_EQ(bad_level.exit_code, 1);
  EXPECT_NE(bad_level.err.find("stores levels 0..2"), std::string::npos) << bad_level.err;
  const testing::CliRun no_placeholder =
      testing::RunMeshvid("decode '" + kGolden + "' -o '" + dir.File("x.obj") + "'", dir);
  EXPECT_EQ(no_placeholder.exit_code, 2);
}

TEST(MvidCliTest, EvalMeasuresADecodedFileAgainstItsOwnFrames) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  ASSERT_EQ(testing::RunMeshvid("decode '" + kGolden + "' -o '" + dir.File("g{frame:02}.obj") +
                                    "' --quiet", dir).exit_code, 0);
  const testing::CliRun run = testing::RunMeshvid(
      "eval --ref '" + dir.File("g{frame:02}.obj") + "' --test '" + kGolden +
          "' --samples 4000 --quiet --json '" + dir.File("e.json") + "'",
      dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(testing::ReadFile(dir.File("e.json")));
  ASSERT_EQ(j["frames"].size(), 6u);
  // OBJ stores positions as shortest round-trip text, so the surfaces are the same.
  EXPECT_LT(j["mean"]["accuracy_rms"].get<double>(), 1e-6);
  EXPECT_EQ(j["mean"]["coverage"], 1.0);
}

TEST(MvidCliTest, EveryOutputGoesIntoFoldersThatDoNotExistYet) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string nested = dir.File("a/b/c");
  const testing::CliRun decode = testing::RunMeshvid(
      "decode '" + kGolden + "' --quiet --frames 0:2 -o '" + nested + "/decoded/f{frame}.ply'" +
          " --json '" + nested + "/json/decode.json'",
      dir);
  ASSERT_EQ(decode.exit_code, 0) << decode.err;
  EXPECT_TRUE(std::filesystem::exists(nested + "/decoded/f1.ply"));
  EXPECT_TRUE(std::filesystem::exists(nested + "/json/decode.json"));
  const testing::CliRun eval = testing::RunMeshvid(
      "eval --ref '" + nested + "/decoded/f{frame}.ply' --test '" + kGolden +
          "' --frames 0:2 --samples 2000 --quiet --json '" + nested + "/eval/e.json'",
      dir);
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  EXPECT_TRUE(std::filesystem::exists(nested + "/eval/e.json"));
  // Nothing but the outputs: no temporary file is left beside them.
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.File("a"))) {
    EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << entry.path();
  }
}

}  // namespace
}  // namespace meshvid
