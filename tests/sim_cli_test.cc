// `meshvid simulate` end to end (the binary path comes from MESHVID_CLI, set by CTest).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/test_util.h"
#include "tools/io/capture.h"

namespace meshvid {
namespace {

TEST(SimulateCliTest, SimulatesTheClothScene) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string out = dir.File("cap");
  const testing::CliRun run =
      testing::RunMeshvid("simulate scene:cloth -o \"" + out + "\" --frames 0:2 --res 160x120", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string log = run.out + run.err;
  EXPECT_NE(log.find("Simulated 2 frames x 3 views (160x120"), std::string::npos) << log;
  EXPECT_NE(log.find("Colour: a procedural albedo fixed to the surface, seen with exposure gains"),
            std::string::npos)
      << log;
  for (const char* name : {"f0000_v0.ply", "f0000_v1.ply", "f0000_v2.ply", "f0001_v0.ply",
                           "f0001_v1.ply", "f0001_v2.ply", "manifest.json", "simulate.json",
                           "ground_truth.obj", "ground_truth.pc2"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(out + "/" + name)) << name;
  }
  EXPECT_FALSE(std::filesystem::exists(out + "/f0002_v0.ply"));
  auto capture = CaptureSequence::Open(out + "/manifest.json");
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  EXPECT_EQ((*capture)->frame_count(), 2);
  EXPECT_EQ((*capture)->view_count(), 3);
  auto view = (*capture)->LoadView(1, 2);
  ASSERT_TRUE(view.ok()) << view.status().ToString();
  EXPECT_GT(view->triangle_count(), 1000u);
  EXPECT_EQ(view->colours.size(), view->vertex_count());
}

TEST(SimulateCliTest, NoColourLeavesColourOut) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string out = dir.File("cap");
  const testing::CliRun run = testing::RunMeshvid(
      "simulate scene:cloth -o \"" + out + "\" --frames 0:1 --res 80x60 --no-colour --json -", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("\"colour\": \"none\""), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("No colour (--no-colour)."), std::string::npos) << run.err;
  auto capture = CaptureSequence::Open(out + "/manifest.json");
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  auto view = (*capture)->LoadView(0, 0);
  ASSERT_TRUE(view.ok()) << view.status().ToString();
  EXPECT_TRUE(view->colours.empty());
}

TEST(SimulateCliTest, BadArgumentsAreUsageErrorsWithAMessage) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string out = " -o \"" + dir.File("cap") + "\" ";
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const Case cases[] = {
      {"scene:cloth" + out + "--res 640by480", 2, "--res '640by480'"},
      {"scene:cloth" + out + "--frames 0:1 --views 0", 2, "--views must be at least 1"},
      {"scene:cloth" + out + "--frames 0:1 --dropout 1", 2, "--dropout"},
      {"scene:cloth" + out + "--frames 200:300", 2, "--frames"},
      {"scene:cloth" + out + "--frames 0:1 --exposure-spread 2", 2, "exposure spread"},
      {"scene:cloth" + out + "--frames 0:1 --colour-noise -1", 2, "colour noise"},
      {"scene:nothing" + out, 1, "scene:arm-block"},
      {"\"" + dir.File("missing.obj") + "\"" + out, 1, "missing.obj"},
  };
  for (const Case& c : cases) {
    const testing::CliRun run = testing::RunMeshvid("simulate " + c.args, dir);
    const std::string log = run.out + run.err;
    EXPECT_EQ(run.exit_code, c.exit_code) << c.args << "\n" << log;
    EXPECT_NE(log.find(c.message), std::string::npos) << c.args << "\n" << log;
  }
  testing::WriteFile(dir.File("blocker"), "x");
  const testing::CliRun blocked = testing::RunMeshvid(
      "simulate scene:cloth -o \"" + dir.File("blocker") + "/sub\" --frames 0:1", dir);
  EXPECT_EQ(blocked.exit_code, 1);
  EXPECT_NE(blocked.err.find("blocker"), std::string::npos) << blocked.err;
}

}  // namespace
}  // namespace meshvid
