// SimulateCapture: the files of a simulated capture, and their determinism.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/test_util.h"
#include "tools/io/capture.h"
#include "tools/io/mesh_sequence.h"
#include "tools/sim/scenes.h"
#include "tools/sim/simulator.h"

namespace meshvid {
namespace {

SimulateOptions SmallOptions() {
  SimulateOptions options;
  options.rig.width = 120;
  options.rig.height = 90;
  options.first_frame = 5;
  options.end_frame = 8;
  options.sensor.seed = 3;
  options.ground_truth_spec = "scene:arm-block";
  return options;
}

TEST(SimulatorTest, WritesViewsManifestAndGroundTruth) {
  testing::TempDir dir;
  const std::string out = dir.File("capture");  // created by the simulator
  auto scene = MakeArmBlockScene();
  long progress_calls = 0;
  auto summary = SimulateCapture(*scene, out, SmallOptions(),
                                 [&](std::string_view, long, long) {
                                   ++progress_calls;
                                   return true;
                                 });
  ASSERT_TRUE(summary.ok()) << summary.status().ToString();
  EXPECT_EQ(summary->frames, 3);
  EXPECT_EQ(summary->views, 3);
  EXPECT_EQ(summary->pixels, 3LL * 3 * 120 * 90);
  EXPECT_GT(summary->hit_pixels, summary->pixels / 20);
  EXPECT_LE(summary->samples, summary->hit_pixels);
  EXPECT_GT(progress_calls, 3);
  for (int f = 0; f < 3; ++f) {
    for (int v = 0; v < 3; ++v) {
      EXPECT_TRUE(std::filesystem::exists(out + "/" + SimulatedViewFileName(f, v)));
    }
  }
  EXPECT_EQ(SimulatedViewFileName(12, 1), "f0012_v1.ply");
  EXPECT_FALSE(std::filesystem::exists(out + "/" + SimulatedViewFileName(3, 0)));

  // The capture reopens with its calibration, views in world coordinates.
  auto capture = CaptureSequence::Open(summary->manifest_path);
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  EXPECT_EQ((*capture)->frame_count(), 3);
  EXPECT_EQ((*capture)->view_count(), 3);
  const CaptureView& view = (*capture)->info().views[1];
  ASSERT_TRUE(view.calibration.intrinsics.has_value());
  EXPECT_EQ(view.calibration.intrinsics->width, 120);
  auto frame = (*capture)->LoadFrame(2);
  ASSERT_TRUE(frame.ok()) << frame.status().ToString();
  auto truth_frame = scene->Frame(7);
  const Eigen::AlignedBox3f truth_box = BoundingBox(*truth_frame);
  for (const TriangleMesh& mesh : *frame) {
    ASSERT_GT(mesh.triangle_count(), 100u);
    const Eigen::AlignedBox3f box = BoundingBox(mesh);
    // Range samples lie on the ground truth (within noise).
    EXPECT_TRUE((box.min().array() >= truth_box.min().array() - 0.01f).all());
    EXPECT_TRUE((box.max().array() <= truth_box.max().array() + 0.01f).all());
  }

  // Ground truth of the simulated frames, and the source offset.
  auto truth = OpenMeshSequence(out + "/ground_truth.obj");
  ASSERT_TRUE(truth.ok()) << truth.status().ToString();
  ASSERT_EQ((*truth)->frame_count(), 3);
  auto truth_last = (*truth)->Frame(2);
  ASSERT_TRUE(truth_last.ok());
  EXPECT_TRUE(truth_last->triangles == truth_frame->triangles);
  for (std::size_t i = 0; i < truth_last->vertex_count(); i += 97) {
    EXPECT_TRUE(truth_last->positions[i].isApprox(truth_frame->positions[i], 1e-6f));
  }
  std::ifstream json_file(out + "/simulate.json");
  const nlohmann::json info = nlohmann::json::parse(json_file);
  EXPECT_EQ(info["source_first_frame"], 5);
  EXPECT_EQ(info["source_end_frame"], 8);
  EXPECT_EQ(info["ground_truth"], "scene:arm-block");
}

TEST(SimulatorTest, SameSeedGivesByteIdenticalFiles) {
  testing::TempDir dir;
  auto scene = MakeArmBlockScene();
  SimulateOptions options = SmallOptions();
  options.sensor.dropout = 0.05;
  ASSERT_TRUE(SimulateCapture(*scene, dir.File("a"), options).ok());
  ASSERT_TRUE(SimulateCapture(*scene, dir.File("b"), options).ok());
  options.sensor.seed = 4;
  ASSERT_TRUE(SimulateCapture(*scene, dir.File("c"), options).ok());
  for (int v = 0; v < 3; ++v) {
    const std::string name = "/" + SimulatedViewFileName(2, v);
    const std::string a = testing::ReadFile(dir.File("a") + name);
    EXPECT_GT(a.size(), 1000u);
    EXPECT_EQ(a, testing::ReadFile(dir.File("b") + name));
    EXPECT_NE(a, testing::ReadFile(dir.File("c") + name));
  }
}

TEST(SimulatorTest, ReportsBadFrameRangesAndUnwritableFolders) {
  testing::TempDir dir;
  auto scene = MakeClothScene({.frame_count = 4});
  SimulateOptions options = SmallOptions();
  options.first_frame = 2;
  options.end_frame = 9;
  auto bad_range = SimulateCapture(*scene, dir.File("x"), options);
  EXPECT_EQ(bad_range.status().code(), StatusCode::kInvalidArgument);
  testing::WriteFile(dir.File("file"), "not a folder");
  auto not_a_folder = SimulateCapture(*scene, dir.File("file"), SimulateOptions());
  EXPECT_FALSE(not_a_folder.ok());
  EXPECT_NE(not_a_folder.status().message().find(dir.File("file")), std::string::npos);
  auto cancelled = SimulateCapture(*scene, dir.File("y"), SimulateOptions(),
                                   [](std::string_view, long, long) { return false; });
  EXPECT_EQ(cancelled.status().code(), StatusCode::kCancelled);
}

}  // namespace
}  // namespace meshvid
