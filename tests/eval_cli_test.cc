// Runs the built `meshvid eval` (path in MESHVID_CLI, set by CTest) on OBJ sequences made in a
// temporary directory, and checks its JSON and exit codes.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/test_util.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

/// Writes planes z = offset + 0.1 t as dir/NAME{frame:04}.obj, t = 0..count-1.
void WritePlaneSequence(const testing::TempDir& dir, const std::string& name, int count,
                        float offset, int resolution) {
  for (int t = 0; t < count; ++t) {
    char file[64];
    std::snprintf(file, sizeof(file), "%s%04d.obj", name.c_str(), t);
    TriangleMesh mesh = testing::MakeGridPlane(1.0f, resolution, offset + 0.1f * t);
    ASSERT_TRUE(WriteMesh(dir.File(file), mesh).ok()) << file;
  }
}

class EvalCliTest : public ::testing::Test {
 protected:
  void SetUp() override { MESHVID_REQUIRE_CLI(); }
  testing::TempDir dir_;
};

TEST_F(EvalCliTest, WritesJsonForTwoObjSequences) {
  WritePlaneSequence(dir_, "ref", 3, 0.0f, 6);
  WritePlaneSequence(dir_, "test", 3, 0.002f, 5);
  const testing::CliRun run = testing::RunMeshvid("eval --ref '" + dir_.File("ref{frame:04}.obj") + "' --test '" +
                              dir_.File("test{frame:04}.obj") +
                              "' --samples 5000 --seed 3 --quiet --json '" +
                              dir_.File("eval.json") + "'", dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(testing::ReadFile(dir_.File("eval.json")));
  EXPECT_EQ(j["settings"]["samples"], 5000);
  EXPECT_EQ(j["settings"]["seed"], 3);
  // Box over all frames: 1 x 1 x 0.2.
  EXPECT_NEAR(j["peak"].get<double>(), std::sqrt(2.04), 1e-6);
  ASSERT_EQ(j["frames"].size(), 3u);
  for (int t = 0; t < 3; ++t) {
    EXPECT_EQ(j["frames"][t]["frame"], t);
    EXPECT_NEAR(j["frames"][t]["accuracy_rms"].get<double>(), 0.002, 1e-6);
    EXPECT_NEAR(j["frames"][t]["hausdorff"].get<double>(), 0.002, 1e-6);
    EXPECT_EQ(j["frames"][t]["coverage"], 1.0);  // 0.002 < 0.25% of 1.43
  }
  EXPECT_NEAR(j["mean"]["completeness_rms"].get<double>(), 0.002, 1e-6);
  // Both averages of the PSNRs, in the JSON and labelled in the table.
  EXPECT_TRUE(j["mean"]["d1_psnr"].is_number());
  EXPECT_TRUE(j["mean"]["d1_psnr_mean_of_frames"].is_number());
  EXPECT_TRUE(j["mean"]["d2_psnr_mean_of_frames"].is_number());
  EXPECT_EQ(j["mean"]["d1_psnr_capped_frames"], 0);
  EXPECT_NE(run.out.find("      mean MSE "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("mean of frames "), std::string::npos) << run.out;
}

TEST_F(EvalCliTest, FrameRangeSelectsFrames) {
  WritePlaneSequence(dir_, "ref", 3, 0.0f, 4);
  const testing::CliRun run = testing::RunMeshvid("eval --ref '" + dir_.File("ref{frame:04}.obj") + "' --test '" +
                              dir_.File("ref{frame:04}.obj") +
                              "' --samples 2000 --frames 1:3 --quiet --json '" +
                              dir_.File("eval.json") + "'", dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(testing::ReadFile(dir_.File("eval.json")));
  ASSERT_EQ(j["frames"].size(), 2u);
  EXPECT_EQ(j["frames"][0]["frame"], 1);
  EXPECT_EQ(j["frames"][0]["d1_psnr"], "inf");
}

TEST_F(EvalCliTest, RefFirstMeasuresAnExcerptAgainstTheWholeReference) {
  WritePlaneSequence(dir_, "ref", 4, 0.0f, 4);
  WritePlaneSequence(dir_, "excerpt", 2, 0.1f, 4);  // the reference's frames 1 and 2
  const std::string command = "eval --ref '" + dir_.File("ref{frame:04}.obj") + "' --test '" +
                              dir_.File("excerpt{frame:04}.obj") + "' --samples 2000 --quiet";
  const testing::CliRun unaligned = testing::RunMeshvid(command, dir_);
  EXPECT_EQ(unaligned.exit_code, 1);
  EXPECT_NE(unaligned.err.find("--ref-first N"), std::string::npos) << unaligned.err;
  const testing::CliRun run = testing::RunMeshvid(
      command + " --ref-first 1 --json '" + dir_.File("eval.json") + "'", dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("test frame t against reference frame t + 1"), std::string::npos)
      << run.out;
  const nlohmann::json j = nlohmann::json::parse(testing::ReadFile(dir_.File("eval.json")));
  EXPECT_EQ(j["settings"]["ref_first"], 1);
  ASSERT_EQ(j["frames"].size(), 2u);
  for (int t = 0; t < 2; ++t) {
    EXPECT_EQ(j["frames"][t]["frame"], t);
    EXPECT_EQ(j["frames"][t]["d1_psnr"], "inf");
  }
}

TEST_F(EvalCliTest, RefFirstZeroMeasuresTheReferencesFirstFrames) {
  WritePlaneSequence(dir_, "ref", 4, 0.0f, 4);
  WritePlaneSequence(dir_, "start", 2, 0.0f, 4);  // the reference's frames 0 and 1
  const testing::CliRun run = testing::RunMeshvid(
      "eval --ref '" + dir_.File("ref{frame:04}.obj") + "' --test '" +
          dir_.File("start{frame:04}.obj") + "' --samples 2000 --quiet --ref-first 0 --json '" +
          dir_.File("eval.json") + "'",
      dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(testing::ReadFile(dir_.File("eval.json")));
  ASSERT_EQ(j["frames"].size(), 2u);
  EXPECT_EQ(j["frames"][1]["d1_psnr"], "inf");
}

TEST_F(EvalCliTest, FrameCountMismatchFails) {
  WritePlaneSequence(dir_, "ref", 3, 0.0f, 4);
  WritePlaneSequence(dir_, "test", 2, 0.0f, 4);
  const testing::CliRun run = testing::RunMeshvid("eval --ref '" + dir_.File("ref{frame:04}.obj") + "' --test '" +
                              dir_.File("test{frame:04}.obj") + "' --samples 1000 --quiet", dir_);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("frame counts differ"), std::string::npos) << run.err;
}

TEST_F(EvalCliTest, MissingTestFileNamesIt) {
  WritePlaneSequence(dir_, "ref", 1, 0.0f, 2);
  const testing::CliRun run = testing::RunMeshvid("eval --ref '" + dir_.File("ref0000.obj") + "' --test '" +
                              dir_.File("absent.obj") + "' --quiet", dir_);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("absent.obj"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace meshvid
