// Tests of the sequence-level driver, its JSON and table, and the test-source adapters.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/test_util.h"
#include "tools/eval/eval_source.h"
#include "tools/eval/evaluation.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

/// A MeshSequence held in memory.
class VectorSequence : public MeshSequence {
 public:
  explicit VectorSequence(std::vector<TriangleMesh> frames) : frames_(std::move(frames)) {}
  int frame_count() const override { return static_cast<int>(frames_.size()); }
  double frame_rate() const override { return 25.0; }
  bool fixed_connectivity() const override { return false; }
  StatusOr<TriangleMesh> Frame(int t) override { return frames_.at(t); }
  std::string description() const override { return "memory"; }

 private:
  std::vector<TriangleMesh> frames_;
};

/// Planes at z = offset + t for frames t = 0..count-1; the first frame spans z 0..0, the box
/// over all frames is 1 x 1 x (count - 1).
VectorSequence Planes(int count, float offset, int resolution = 6) {
  std::vector<TriangleMesh> frames;
  for (int t = 0; t < count; ++t) {
    frames.push_back(testing::MakeGridPlane(1.0f, resolution, offset + t));
  }
  return VectorSequence(std::move(frames));
}

EvalOptions SmallOptions() {
  EvalOptions options;
  options.samples = 4000;
  return options;
}

TEST(EvalSequenceTest, PeakIsTheBoundingBoxDiagonalOverAllFrames) {
  VectorSequence ref = Planes(3, 0.0f);
  const auto diagonal = SequenceBoundingBoxDiagonal(ref);
  ASSERT_TRUE(diagonal.ok());
  EXPECT_NEAR(*diagonal, std::sqrt(1.0 + 1.0 + 4.0), 1e-6);
}

TEST(EvalSequenceTest, PerFrameResultsAndMean) {
  VectorSequence ref = Planes(3, 0.0f);
  VectorSequence test = Planes(3, 0.01f, 5);
  const auto result = EvaluateSequences(ref, test, SmallOptions());
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  const double peak = std::sqrt(6.0);
  EXPECT_NEAR(result->peak, peak, 1e-6);
  EXPECT_DOUBLE_EQ(result->coverage_tolerance, kDefaultCoverageToleranceRatio * result->peak);
  ASSERT_EQ(result->frames.size(), 3u);
  for (int t = 0; t < 3; ++t) {
    EXPECT_EQ(result->frames[t].frame, t);
    EXPECT_NEAR(result->frames[t].accuracy_rms, 0.01, 1e-6);
  }
  EXPECT_EQ(result->mean.frame, -1);
  EXPECT_NEAR(result->mean.accuracy_rms, 0.01, 1e-6);
  const double mean_d2 = (result->frames[0].d2_mse + result->frames[1].d2_mse +
                          result->frames[2].d2_mse) / 3;
  EXPECT_DOUBLE_EQ(result->mean.d2_mse, mean_d2);
  EXPECT_DOUBLE_EQ(result->mean.d2_psnr, PsnrFromMse(mean_d2, result->peak));
}

TEST(EvalSequenceTest, FrameCountMismatchIsAClearError) {
  VectorSequence ref = Planes(3, 0.0f);
  VectorSequence test = Planes(2, 0.0f);
  const auto result = EvaluateSequences(ref, test, SmallOptions());
  ASSERT_EQ(result.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(result.status().message().find("frame counts differ"), std::string::npos)
      << result.status().message();
  EXPECT_NE(result.status().message().find("has 3 frames"), std::string::npos);
  // A range both sequences hold is fine; one past the test's end is not.
  EvalOptions options = SmallOptions();
  options.end_frame = 2;
  EXPECT_TRUE(EvaluateSequences(ref, test, options).ok());
  options.end_frame = 3;
  EXPECT_EQ(EvaluateSequences(ref, test, options).status().code(),
            StatusCode::kInvalidArgument);
}

TEST(EvalSequenceTest, RangePeakOverrideAndCancel) {
  VectorSequence ref = Planes(4, 0.0f);
  VectorSequence test = Planes(4, 0.0f);
  EvalOptions options = SmallOptions();
  options.first_frame = 1;
  options.end_frame = 3;
  options.peak = 10.0;
  options.coverage_tolerance = 0.5;
  const auto result = EvaluateSequences(ref, test, options);
  ASSERT_TRUE(result.ok());
  ASSERT_EQ(result->frames.size(), 2u);
  EXPECT_EQ(result->frames[0].frame, 1);
  EXPECT_EQ(result->frames[1].frame, 2);
  EXPECT_EQ(result->peak, 10.0);
  EXPECT_EQ(result->coverage_tolerance, 0.5);
  const auto cancelled = EvaluateSequences(
      ref, test, options, [](std::string_view, long done, long) { return done < 1; });
  EXPECT_EQ(cancelled.status().code(), StatusCode::kCancelled);
}

TEST(EvalSequenceTest, JsonHasSettingsPeakFramesAndMean) {
  VectorSequence ref = Planes(2, 0.0f);
  VectorSequence test = Planes(2, 0.0f);
  EvalOptions options = SmallOptions();
  options.seed = 9;
  const auto result = EvaluateSequences(ref, test, options);
  ASSERT_TRUE(result.ok());
  const nlohmann::json j = nlohmann::json::parse(EvalResultToJson(*result));
  EXPECT_EQ(j["settings"]["samples"], 4000);
  EXPECT_EQ(j["settings"]["seed"], 9);
  EXPECT_EQ(j["settings"]["first_frame"], 0);
  EXPECT_EQ(j["settings"]["end_frame"], 2);
  EXPECT_EQ(j["settings"]["ref"], "memory");
  EXPECT_NEAR(j["peak"].get<double>(), std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(j["coverage_tolerance"].get<double>(), 0.0025 * std::sqrt(3.0), 1e-9);
  ASSERT_EQ(j["frames"].size(), 2u);
  for (const char* key : {"frame", "d1_psnr", "d2_psnr", "d1_mse", "d2_mse", "accuracy_rms",
                          "completeness_rms", "hausdorff", "coverage"}) {
    EXPECT_TRUE(j["frames"][1].contains(key)) << key;
  }
  // Identical surfaces: infinite PSNR is written as "inf", in the frames and the mean.
  EXPECT_EQ(j["frames"][1]["d1_psnr"], "inf");
  EXPECT_EQ(j["mean"]["d2_psnr"], "inf");
  EXPECT_EQ(j["mean"]["coverage"], 1.0);
  EXPECT_FALSE(j["mean"].contains("frame"));

  const std::string table = FormatEvalTable(*result);
  EXPECT_NE(table.find("D1 PSNR"), std::string::npos);
  EXPECT_NE(table.find("  mean      inf      inf"), std::string::npos) << table;
}

TEST(EvalSequenceTest, WriteJsonNamesTheFileOnFailure) {
  EvalResult result;
  testing::TempDir dir;
  testing::WriteFile(dir.File("file"), "a file where a folder should be");
  const Status status = WriteEvalJson(result, dir.File("file/eval.json"));
  EXPECT_EQ(status.code(), StatusCode::kIoError);
  EXPECT_NE(status.message().find(dir.File("file/eval.json")), std::string::npos);
}

TEST(EvalSourceTest, CaptureSpecsAreRecognised) {
  EXPECT_TRUE(LooksLikeCapture("cap/manifest.json"));
  EXPECT_TRUE(LooksLikeCapture("bunny/bun.conf"));
  EXPECT_TRUE(LooksLikeCapture("cap/f{frame:04}_v{view}.ply"));
  EXPECT_FALSE(LooksLikeCapture("out/f{frame:04}.obj"));
  EXPECT_FALSE(LooksLikeCapture("samba.obj"));
}

TEST(EvalSourceTest, CaptureFrameIsTheUnionOfItsViews) {
  testing::TempDir dir;
  for (int frame = 0; frame < 2; ++frame) {
    for (int view = 0; view < 2; ++view) {
      TriangleMesh mesh = testing::MakeGridPlane(1.0f, 2, static_cast<float>(view));
      mesh.normals.clear();
      std::string name = "f";  // f<frame>_v<view>.ply
      name += std::to_string(frame);
      name += "_v";
      name += std::to_string(view);
      name += ".ply";
      const std::string path = dir.File(name);
      ASSERT_TRUE(WriteMesh(path, mesh).ok());
    }
  }
  auto source = OpenEvalTestSource(dir.File("f{frame}_v{view}.ply"));
  ASSERT_TRUE(source.ok()) << source.status().ToString();
  EXPECT_EQ((*source)->frame_count(), 2);
  const auto frame = (*source)->Frame(1);
  ASSERT_TRUE(frame.ok()) << frame.status().ToString();
  EXPECT_EQ(frame->vertex_count(), 18u);
  EXPECT_EQ(frame->triangle_count(), 16u);
  EXPECT_NEAR(SurfaceArea(*frame), 2.0, 1e-6);
}

TEST(EvalSourceTest, StanfordBunnyScansAreOneFrame) {
  MESHVID_REQUIRE_SHARED_DATA();
  auto source = OpenEvalTestSource(shared_data + "/bunny-range/bun.conf");
  ASSERT_TRUE(source.ok()) << source.status().ToString();
  EXPECT_EQ((*source)->frame_count(), 1);
  const auto frame = (*source)->Frame(0);
  ASSERT_TRUE(frame.ok()) << frame.status().ToString();
  EXPECT_GT(frame->triangle_count(), 100000u);
}

}  // namespace
}  // namespace meshvid
