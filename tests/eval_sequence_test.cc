// Tests of the sequence-level driver, its JSON and table, and the test-source adapters.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
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

/// A frame measured with D1 and D2 MSE `mse` at peak p = 1/sqrt(3) (3 p^2 = 1, so a PSNR is
/// -10 log10(MSE)).
FrameMetrics FrameWithMse(int t, double mse) {
  FrameMetrics m;
  m.frame = t;
  m.d1_mse = m.d2_mse = mse;
  m.d1_psnr = m.d2_psnr = PsnrFromMse(mse, 1 / std::sqrt(3.0));
  return m;
}

TEST(EvalSequenceTest, MeanOfFramesAndPsnrOfMeanMseDifferWhenFramesDo) {
  // 30 frames whose last half diverged: 50 dB (MSE 1e-5) then 30 dB (MSE 1e-3).
  std::vector<FrameMetrics> frames;
  for (int t = 0; t < 30; ++t) frames.push_back(FrameWithMse(t, t < 15 ? 1e-5 : 1e-3));
  EXPECT_NEAR(frames[0].d1_psnr, 50, 1e-9);
  EXPECT_NEAR(frames[29].d1_psnr, 30, 1e-9);
  const FrameMetrics mean = MeanFrameMetrics(frames, 1 / std::sqrt(3.0));
  const PsnrMeanOfFrames of_frames = MeanOfFramePsnrs(frames);
  // The mean of the PSNRs: (50 + 30) / 2 = 40 dB.
  EXPECT_NEAR(of_frames.d1_psnr, 40, 1e-9);
  EXPECT_NEAR(of_frames.d2_psnr, 40, 1e-9);
  EXPECT_EQ(of_frames.d1_capped_frames, 0);
  // The PSNR of the mean MSE, 5.05e-4: 32.97 dB, dominated by the bad half.
  EXPECT_NEAR(mean.d1_psnr, -10 * std::log10(5.05e-4), 1e-9);
  EXPECT_NEAR(mean.d1_psnr, 32.97, 0.01);
  EXPECT_GT(of_frames.d1_psnr - mean.d1_psnr, 7);
  // Equal frames: both averages agree.
  const std::vector<FrameMetrics> steady(4, FrameWithMse(0, 1e-4));
  EXPECT_NEAR(MeanOfFramePsnrs(steady).d1_psnr,
              MeanFrameMetrics(steady, 1 / std::sqrt(3.0)).d1_psnr, 1e-9);
  EXPECT_TRUE(std::isnan(MeanOfFramePsnrs({}).d1_psnr));
}

TEST(EvalSequenceTest, ExactFramesAreCappedInTheMeanOfFramesAndCounted) {
  // One exact frame (PSNR inf) and one at 30 dB: the exact frame counts as 100 dB.
  const std::vector<FrameMetrics> frames = {FrameWithMse(0, 0), FrameWithMse(1, 1e-3)};
  EXPECT_TRUE(std::isinf(frames[0].d1_psnr));
  const PsnrMeanOfFrames of_frames = MeanOfFramePsnrs(frames);
  EXPECT_NEAR(of_frames.d1_psnr, (kFramePsnrCapDb + 30) / 2, 1e-9);
  EXPECT_EQ(of_frames.d1_capped_frames, 1);
  EXPECT_EQ(of_frames.d2_capped_frames, 1);
  // A finite PSNR above the cap is capped too.
  const PsnrMeanOfFrames high = MeanOfFramePsnrs({FrameWithMse(0, 1e-12)});  // 120 dB
  EXPECT_DOUBLE_EQ(high.d1_psnr, kFramePsnrCapDb);
  EXPECT_EQ(high.d1_capped_frames, 1);
}

TEST(EvalSequenceTest, OneBadFrameWeighsMoreInThePsnrOfTheMeanMse) {
  // Frame 0 is 0.001 off, frame 1 is 0.1 off (100x the distance, 40 dB worse).
  VectorSequence ref(
      {testing::MakeGridPlane(1.0f, 6, 0.0f), testing::MakeGridPlane(1.0f, 6, 1.0f)});
  VectorSequence test(
      {testing::MakeGridPlane(1.0f, 6, 0.001f), testing::MakeGridPlane(1.0f, 6, 1.1f)});
  const auto result = EvaluateSequences(ref, test, SmallOptions());
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  const std::vector<FrameMetrics>& f = result->frames;
  ASSERT_EQ(f.size(), 2u);
  EXPECT_NEAR(f[0].d1_psnr - f[1].d1_psnr, 40, 0.5);
  EXPECT_NEAR(result->mean_of_frames.d1_psnr, (f[0].d1_psnr + f[1].d1_psnr) / 2, 1e-9);
  EXPECT_NEAR(result->mean_of_frames.d2_psnr, (f[0].d2_psnr + f[1].d2_psnr) / 2, 1e-9);
  EXPECT_DOUBLE_EQ(result->mean.d1_psnr,
                   PsnrFromMse((f[0].d1_mse + f[1].d1_mse) / 2, result->peak));
  // The bad frame's MSE is 1e4 x the good one's: the mean MSE is about half of it (-3 dB from
  // the bad frame), while the mean of frames lies halfway (+20 dB).
  EXPECT_NEAR(result->mean.d1_psnr, f[1].d1_psnr + 3.0, 0.1);
  EXPECT_GT(result->mean_of_frames.d1_psnr - result->mean.d1_psnr, 15);

  const nlohmann::json j = nlohmann::json::parse(EvalResultToJson(*result));
  EXPECT_NEAR(j["mean"]["d1_psnr"].get<double>(), result->mean.d1_psnr, 1e-9);
  EXPECT_NEAR(j["mean"]["d1_psnr_mean_of_frames"].get<double>(), result->mean_of_frames.d1_psnr,
              1e-9);
  EXPECT_NEAR(j["mean"]["d2_psnr_mean_of_frames"].get<double>(), result->mean_of_frames.d2_psnr,
              1e-9);
  EXPECT_EQ(j["mean"]["d1_psnr_capped_frames"], 0);
  const std::string table = FormatEvalTable(*result);
  char row[64];
  std::snprintf(row, sizeof(row), "mean of frames %8.2f %8.2f\n", result->mean_of_frames.d1_psnr,
                result->mean_of_frames.d2_psnr);
  EXPECT_NE(table.find(row), std::string::npos) << table;
  std::snprintf(row, sizeof(row), "      mean MSE %8.2f %8.2f ", result->mean.d1_psnr,
                result->mean.d2_psnr);
  EXPECT_NE(table.find(row), std::string::npos) << table;
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

TEST(EvalSequenceTest, RefFirstMeasuresTheTestFromALaterReferenceFrame) {
  // A test encoded from the reference's frames 2..3 (planes z = 2.01, 3.01).
  VectorSequence ref = Planes(5, 0.0f);
  VectorSequence test = Planes(2, 2.01f);
  const auto unaligned = EvaluateSequences(ref, test, SmallOptions());
  ASSERT_EQ(unaligned.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(unaligned.status().message().find("--ref-first"), std::string::npos)
      << unaligned.status().message();
  EvalOptions options = SmallOptions();
  options.ref_first = 2;
  const auto result = EvaluateSequences(ref, test, options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_EQ(result->ref_first, 2);
  ASSERT_EQ(result->frames.size(), 2u);
  // Measured and sampled as the same frames of a test as long as the reference.
  VectorSequence whole_test = Planes(5, 0.01f);
  EvalOptions whole = SmallOptions();
  whole.first_frame = 2;
  whole.end_frame = 4;
  const auto expected = EvaluateSequences(ref, whole_test, whole);
  ASSERT_TRUE(expected.ok());
  for (int t = 0; t < 2; ++t) {
    EXPECT_EQ(result->frames[t].frame, t);
    EXPECT_NEAR(result->frames[t].accuracy_rms, 0.01, 1e-6);
    EXPECT_DOUBLE_EQ(result->frames[t].d1_psnr, expected->frames[t].d1_psnr);
    EXPECT_DOUBLE_EQ(result->frames[t].completeness_rms, expected->frames[t].completeness_rms);
  }
  EXPECT_DOUBLE_EQ(result->peak, expected->peak);  // the whole reference's
  // The reference must hold the test's frames from ref_first on.
  options.ref_first = 4;
  const auto beyond = EvaluateSequences(ref, test, options);
  ASSERT_EQ(beyond.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(beyond.status().message().find("1 frames from its frame 4 on"), std::string::npos)
      << beyond.status().message();
  options.ref_first = -1;
  EXPECT_EQ(EvaluateSequences(ref, test, options).status().code(),
            StatusCode::kInvalidArgument);
}

TEST(EvalSequenceTest, RefFirstZeroMeasuresTheReferencesFirstFrames) {
  // A test encoded from the reference's frames 0..1 (--frames 0:2): unset, the counts must
  // match; given as 0, the reference may run on past the test.
  VectorSequence ref = Planes(5, 0.0f);
  VectorSequence test = Planes(2, 0.01f);
  EXPECT_EQ(EvaluateSequences(ref, test, SmallOptions()).status().code(),
            StatusCode::kInvalidArgument);
  EvalOptions options = SmallOptions();
  options.ref_first = 0;
  const auto result = EvaluateSequences(ref, test, options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  ASSERT_EQ(result->frames.size(), 2u);
  for (const FrameMetrics& m : result->frames) EXPECT_NEAR(m.accuracy_rms, 0.01, 1e-6);
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
  // The mean of frames: each exact frame counted as the cap, and counted.
  EXPECT_EQ(j["frame_psnr_cap"], kFramePsnrCapDb);
  EXPECT_EQ(j["mean"]["d1_psnr_mean_of_frames"], kFramePsnrCapDb);
  EXPECT_EQ(j["mean"]["d2_psnr_mean_of_frames"], kFramePsnrCapDb);
  EXPECT_EQ(j["mean"]["d1_psnr_capped_frames"], 2);
  EXPECT_EQ(j["mean"]["d2_psnr_capped_frames"], 2);

  const std::string table = FormatEvalTable(*result);
  EXPECT_NE(table.find("D1 PSNR"), std::string::npos);
  EXPECT_NE(table.find("      mean MSE      inf      inf"), std::string::npos) << table;
  EXPECT_NE(table.find("mean of frames   100.00   100.00\n"), std::string::npos) << table;
  EXPECT_NE(table.find("mean MSE: PSNR of the mean MSE over frames"), std::string::npos);
  EXPECT_NE(table.find("mean of frames: mean of the per-frame PSNRs (MPEG CTC), each counted as "
                       "at most 100 dB; frames capped: D1 2, D2 2."),
            std::string::npos)
      << table;
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
