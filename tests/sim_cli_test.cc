// `meshvid simulate` end to end (the binary path comes from MESHVID_CLI, set by CTest).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/test_util.h"
#include "tools/io/capture.h"

namespace meshvid {
namespace {

/// Runs `meshvid ARGS`, output to `log`; returns the exit code (-1 if it did not exit).
int RunCli(const std::string& args, const std::string& log) {
  const std::string command =
      std::string("\"") + std::getenv("MESHVID_CLI") + "\" " + args + " > \"" + log + "\" 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

#define MESHVID_REQUIRE_CLI()                                                   \
  if (std::getenv("MESHVID_CLI") == nullptr) GTEST_SKIP() << "MESHVID_CLI is not set; " \
                                                 "run through ctest"

TEST(SimulateCliTest, SimulatesTheClothScene) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string out = dir.File("cap");
  ASSERT_EQ(RunCli("simulate scene:cloth -o \"" + out + "\" --frames 0:2 --res 160x120",
                   dir.File("log")),
            0)
      << testing::ReadFile(dir.File("log"));
  const std::string log = testing::ReadFile(dir.File("log"));
  EXPECT_NE(log.find("Simulated 2 frames x 3 views (160x120"), std::string::npos) << log;
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
      {"scene:nothing" + out, 1, "scene:arm-block"},
      {"\"" + dir.File("missing.obj") + "\"" + out, 1, "missing.obj"},
  };
  for (const Case& c : cases) {
    const int code = RunCli("simulate " + c.args, dir.File("log"));
    const std::string log = testing::ReadFile(dir.File("log"));
    EXPECT_EQ(code, c.exit_code) << c.args << "\n" << log;
    EXPECT_NE(log.find(c.message), std::string::npos) << c.args << "\n" << log;
  }
  testing::WriteFile(dir.File("blocker"), "x");
  EXPECT_EQ(RunCli("simulate scene:cloth -o \"" + dir.File("blocker") + "/sub\" --frames 0:1",
                   dir.File("log")),
            1);
  EXPECT_NE(testing::ReadFile(dir.File("log")).find("blocker"), std::string::npos);
}

}  // namespace
}  // namespace meshvid
