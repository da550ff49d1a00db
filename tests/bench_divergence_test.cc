// The divergence check (tools/bench/bench_divergence.h) on fake records, and the per-frame
// figures read from eval JSON (tools/bench/eval_figures.h), also for records written before
// they were recorded.
#include "tools/bench/bench_divergence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "tests/bench_fake_records.h"
#include "tests/test_util.h"
#include "tools/bench/eval_figures.h"

namespace meshvid {
namespace {

BenchPoint* Point(BenchRecord& r, const char* method, const char* codec, int quality, int level) {
  BenchPoint* p = FindPoint(r, method, codec, quality, level);
  EXPECT_NE(p, nullptr) << method << " " << codec << " " << quality << " L" << level;
  return p;
}

TEST(BenchDivergenceTest, DefaultsAreTheEncoders) {
  EXPECT_EQ(DefaultCodecName(), "av1");
  EXPECT_EQ(DefaultQuality(), 40);
}

TEST(BenchDivergenceTest, ShareWithinWorstFrameAndPsnrOfTheFakeRecord) {
  const BenchRecord record = testing::FakeRecord();
  const DivergenceCheck& d = record.divergence;
  EXPECT_TRUE(d.has_default);
  EXPECT_TRUE(d.has_baseline);
  EXPECT_TRUE(d.has_frames);
  EXPECT_EQ(d.note, "");
  EXPECT_EQ(d.codec, "av1");
  EXPECT_EQ(d.quality, 40);
  EXPECT_EQ(d.level, 1);  // the finest level of the AV1 q40 points
  EXPECT_EQ(d.baseline_bits, 14);
  EXPECT_EQ(d.psnr, kPsnrMeanOfFrames);
  EXPECT_EQ(d.frames, 10);
  EXPECT_EQ(d.frames_within, 9);
  EXPECT_DOUBLE_EQ(d.share_within, 0.9);
  EXPECT_FALSE(d.share_met);
  EXPECT_EQ(d.worst_frame, 7);
  EXPECT_DOUBLE_EQ(d.worst_meshvid_accuracy_rms, 0.0031);
  EXPECT_DOUBLE_EQ(d.worst_baseline_accuracy_rms, 0.002);
  EXPECT_DOUBLE_EQ(d.worst_ratio, 0.0031 / 0.002);
  EXPECT_DOUBLE_EQ(d.meshvid_d1_psnr, 35);
  EXPECT_DOUBLE_EQ(d.baseline_d1_psnr, 45);
  EXPECT_FALSE(d.psnr_met);
  const std::string line = DescribeDivergence(d);
  EXPECT_NE(line.find("av1 q40 L1 against the baseline's 14 bits: 9/10 frames within 1.25x "
                      "(90.0%, goal 95%: missed), worst frame 7 (1.55x"),
            std::string::npos)
      << line;
  EXPECT_NE(line.find("D1 PSNR 35.00 against 45.00 dB (missed)"), std::string::npos) << line;
}

TEST(BenchDivergenceTest, GoalsAreMetAtTheLimitAndAFrameWithoutAFigureCountsAgainst) {
  BenchRecord r = testing::FakeRecord();
  BenchPoint* m = Point(r, kMethodMeshvid, "av1", 40, 1);
  BenchPoint* b = Point(r, kMethodBaseline, "draco", 14, -1);
  b->frame_accuracy_rms.assign(10, 0.5);
  m->frame_accuracy_rms.assign(10, 0.25);
  m->frame_accuracy_rms[2] = 0.625;  // exactly 1.25x: within
  m->d1_psnr_mean_of_frames = 45;    // equal to the baseline's best: met
  ComputeDivergence(r);
  EXPECT_EQ(r.divergence.frames_within, 10);
  EXPECT_TRUE(r.divergence.share_met);
  EXPECT_TRUE(r.divergence.psnr_met);
  EXPECT_EQ(r.divergence.worst_frame, 2);
  EXPECT_DOUBLE_EQ(r.divergence.worst_ratio, 1.25);

  // 19 of 20 frames within is 95%: met. A frame without meshvid's figure is outside, and the
  // worst; 0 against 0 is within.
  m->frames = b->frames = 20;
  m->frame_accuracy_rms.assign(20, 0.5);
  b->frame_accuracy_rms.assign(20, 0.5);
  m->frame_d1_psnr.assign(20, 45);
  b->frame_d1_psnr.assign(20, 45);
  m->frame_accuracy_rms[4] = 2;  // 4x
  m->frame_accuracy_rms[11] = std::numeric_limits<double>::quiet_NaN();
  m->frame_accuracy_rms[12] = b->frame_accuracy_rms[12] = 0;
  ComputeDivergence(r);
  EXPECT_EQ(r.divergence.frames, 20);
  EXPECT_EQ(r.divergence.frames_within, 18);
  EXPECT_FALSE(r.divergence.share_met);
  EXPECT_EQ(r.divergence.worst_frame, 11);
  EXPECT_TRUE(std::isnan(r.divergence.worst_ratio));
  m->frame_accuracy_rms[11] = 0.5;
  ComputeDivergence(r);
  EXPECT_EQ(r.divergence.frames_within, 19);
  EXPECT_DOUBLE_EQ(r.divergence.share_within, 0.95);
  EXPECT_TRUE(r.divergence.share_met);
  EXPECT_EQ(r.divergence.worst_frame, 4);
  EXPECT_DOUBLE_EQ(r.divergence.worst_ratio, 4);
  // The baseline exact on a frame meshvid is not: an infinite ratio.
  b->frame_accuracy_rms[0] = 0;
  ComputeDivergence(r);
  EXPECT_EQ(r.divergence.worst_frame, 0);
  EXPECT_TRUE(std::isinf(r.divergence.worst_ratio));
  // Different frame counts: the frames both have, said in the note.
  b->frames = 21;
  b->frame_accuracy_rms.push_back(0.5);
  b->frame_d1_psnr.push_back(45);
  ComputeDivergence(r);
  EXPECT_EQ(r.divergence.frames, 20);
  EXPECT_NE(r.divergence.note.find("meshvid has 20 frames, the baseline 21"), std::string::npos)
      << r.divergence.note;
}

TEST(BenchDivergenceTest, TheDefaultPointIsTheDefaultEncodeAtItsFinestLevel) {
  BenchRecord r = testing::FakeRecord();
  // Without the AV1 q40 encode in the record: the finest level among its points.
  EXPECT_EQ(DefaultPointLevel(r), 1);
  const BenchPoint* found = FindDefaultPoint(r);
  ASSERT_NE(found, nullptr);
  EXPECT_EQ(found->codec, "av1");
  EXPECT_EQ(found->quality, 40);
  EXPECT_EQ(found->level, 1);
  // Not another quality, codec or level: an HEVC q40 point at a finer level changes nothing.
  BenchPoint hevc = *found;
  hevc.codec = "hevc";
  hevc.level = 3;
  UpsertPoint(r, hevc);
  BenchPoint q20 = *found;
  q20.quality = 20;
  q20.level = 2;
  UpsertPoint(r, q20);
  EXPECT_EQ(DefaultPointLevel(r), 1);
  // With the encode: the level its file stores, even if that point is missing.
  BenchEncode encode;
  encode.method = kMethodMeshvid;
  encode.codec = "av1";
  encode.quality = 40;
  encode.ok = true;
  encode.levels = 2;
  UpsertEncode(r, encode);
  EXPECT_EQ(DefaultPointLevel(r), 2);
  EXPECT_EQ(FindDefaultPoint(r), nullptr);
  ComputeDivergence(r);
  EXPECT_FALSE(r.divergence.has_default);
  EXPECT_FALSE(r.divergence.has_frames);
  EXPECT_EQ(r.divergence.level, 2);
  EXPECT_NE(r.divergence.note.find("no av1 q40 level 2 point"), std::string::npos)
      << r.divergence.note;
  // Measured but failed: no check, and the note says so (no fallback to a coarser level).
  BenchPoint failed = *found;
  failed.level = 2;
  failed.ok = false;
  UpsertPoint(r, failed);
  ComputeDivergence(r);
  EXPECT_FALSE(r.divergence.has_default);
  EXPECT_NE(r.divergence.note.find("av1 q40 level 2 failed"), std::string::npos)
      << r.divergence.note;
  FindPoint(r, kMethodMeshvid, "av1", 40, 2)->ok = true;
  ComputeDivergence(r);
  EXPECT_TRUE(r.divergence.has_default);
  EXPECT_EQ(r.divergence.level, 2);
}

TEST(BenchDivergenceTest, TheBaselineBestHasTheHighestMeanD1Psnr) {
  BenchRecord r = testing::FakeRecord();
  ASSERT_NE(FindBaselineBest(r), nullptr);
  EXPECT_EQ(FindBaselineBest(r)->quality, 14);
  // The PSNR of the mean MSE does not decide: 12 bits best on the mean of frames only.
  Point(r, kMethodBaseline, "draco", 12, -1)->d1_psnr_mean_of_frames = 46;
  Point(r, kMethodBaseline, "draco", 12, -1)->d1_psnr = 20;
  EXPECT_EQ(FindBaselineBest(r)->quality, 12);
  // A failed point does not count; of equal PSNRs the one with fewer bytes.
  Point(r, kMethodBaseline, "draco", 10, -1)->d1_psnr_mean_of_frames = 50;
  Point(r, kMethodBaseline, "draco", 10, -1)->ok = false;
  Point(r, kMethodBaseline, "draco", 14, -1)->d1_psnr_mean_of_frames = 46;
  EXPECT_EQ(FindBaselineBest(r)->quality, 12);
  ComputeDivergence(r);
  EXPECT_EQ(r.divergence.baseline_bits, 12);
  EXPECT_DOUBLE_EQ(r.divergence.baseline_d1_psnr, 46);
  // No successful baseline point: no check.
  for (BenchPoint& p : r.points) p.ok = p.ok && p.method != kMethodBaseline;
  EXPECT_EQ(FindBaselineBest(r), nullptr);
  ComputeDivergence(r);
  EXPECT_FALSE(r.divergence.has_baseline);
  EXPECT_NE(r.divergence.note.find("no successful baseline point"), std::string::npos);
}

TEST(BenchDivergenceTest, EvalJsonGivesTheMeansAndThePerFrameFigures) {
  const std::string text = R"({
    "frames": [
      {"frame": 0, "d1_psnr": 61.23456789, "accuracy_rms": 0.00123456789},
      {"frame": 1, "d1_psnr": "inf", "accuracy_rms": 0.0},
      {"frame": 2, "d1_psnr": null}
    ],
    "mean": {"d1_psnr": 60.5, "d2_psnr": "inf", "d1_psnr_mean_of_frames": 70.1,
             "d2_psnr_mean_of_frames": 100, "accuracy_rms": 0.001, "completeness_rms": 0.002,
             "hausdorff": 0.01, "coverage": 0.93}})";
  auto figures = ParseEvalFigures(text, "x.eval.json");
  ASSERT_TRUE(figures.ok()) << figures.status().ToString();
  EXPECT_EQ(figures->frames, 3);
  EXPECT_DOUBLE_EQ(figures->d1_psnr, 60.5);
  EXPECT_TRUE(std::isinf(figures->d2_psnr));
  EXPECT_DOUBLE_EQ(figures->d1_psnr_mean_of_frames, 70.1);
  EXPECT_DOUBLE_EQ(figures->coverage, 0.93);
  ASSERT_EQ(figures->frame_accuracy_rms.size(), 3u);
  ASSERT_EQ(figures->frame_d1_psnr.size(), 3u);
  // Rounded to 6 significant digits, as records keep them.
  EXPECT_DOUBLE_EQ(figures->frame_accuracy_rms[0], 0.00123457);
  EXPECT_DOUBLE_EQ(figures->frame_d1_psnr[0], 61.2346);
  EXPECT_TRUE(std::isinf(figures->frame_d1_psnr[1]));
  EXPECT_EQ(figures->frame_accuracy_rms[1], 0);
  EXPECT_TRUE(std::isnan(figures->frame_accuracy_rms[2]));
  EXPECT_TRUE(std::isnan(figures->frame_d1_psnr[2]));
  BenchPoint point;
  SetEvalFigures(*figures, &point);
  EXPECT_EQ(point.frames, 3);
  EXPECT_TRUE(HasFrameFigures(point));
  EXPECT_DOUBLE_EQ(point.accuracy_rms, 0.001);

  EXPECT_EQ(ParseEvalFigures("{\"frames\": []}", "y").status().code(), StatusCode::kCorrupt);
  EXPECT_EQ(ParseEvalFigures("[", "z").status().code(), StatusCode::kCorrupt);
}

TEST(BenchDivergenceTest, OlderPointsAreFilledFromTheirEvalJsonInTheWorkFolder) {
  testing::TempDir dir;
  const BenchRecord complete = testing::FakeRecord();
  auto older = ParseBenchRecord(testing::RecordJsonWithoutFrameFigures(), "fake-3-arc.json");
  ASSERT_TRUE(older.ok()) << older.status().ToString();
  BenchRecord r = *older;
  for (const BenchPoint& p : r.points) EXPECT_FALSE(HasFrameFigures(p));
  // Without per-frame figures the check still compares the D1 PSNRs.
  ComputeDivergence(r);
  EXPECT_TRUE(r.divergence.has_default);
  EXPECT_FALSE(r.divergence.has_frames);
  EXPECT_DOUBLE_EQ(r.divergence.meshvid_d1_psnr, 35);
  EXPECT_NE(r.divergence.note.find("no per-frame figures"), std::string::npos);

  // The work folder holds the eval JSON of the default point and the baseline's best, and one
  // of another evaluation (other means) for AV1 q20 level 1.
  BenchRecord copy = complete;
  const BenchPoint& m = *Point(copy, kMethodMeshvid, "av1", 40, 1);
  const BenchPoint& b = *Point(copy, kMethodBaseline, "draco", 14, -1);
  BenchPoint other = *Point(copy, kMethodMeshvid, "av1", 20, 1);
  EXPECT_EQ(PointWorkStem(m), "av1-q40-L1");
  EXPECT_EQ(PointWorkStem(b), "draco-b14");
  const std::string work = dir.File("work");
  EXPECT_EQ(EvalJsonPath(work, r, m), work + "/fake-3-arc/av1-q40-L1.eval.json");
  std::filesystem::create_directories(work + "/fake-3-arc");
  testing::WriteFile(EvalJsonPath(work, r, m), testing::FakeEvalJson(m));
  testing::WriteFile(EvalJsonPath(work, r, b), testing::FakeEvalJson(b));
  const std::string other_path = EvalJsonPath(work, r, other);
  other.accuracy_rms *= 2;
  testing::WriteFile(other_path, testing::FakeEvalJson(other));
  EXPECT_EQ(BackfillFrameFigures(r, work), 2);
  const BenchPoint& filled = *Point(r, kMethodMeshvid, "av1", 40, 1);
  EXPECT_TRUE(HasFrameFigures(filled));
  EXPECT_EQ(filled.frame_accuracy_rms, m.frame_accuracy_rms);
  EXPECT_EQ(filled.frame_d1_psnr, m.frame_d1_psnr);
  EXPECT_TRUE(HasFrameFigures(*Point(r, kMethodBaseline, "draco", 14, -1)));
  EXPECT_FALSE(HasFrameFigures(*Point(r, kMethodMeshvid, "av1", 20, 1)));     // not its eval
  EXPECT_FALSE(HasFrameFigures(*Point(r, kMethodBaseline, "draco", 8, -1)));  // no file
  BenchPoint* q20 = Point(r, kMethodMeshvid, "av1", 20, 1);
  const Status mismatch = FillFrameFiguresFromEvalJson(other_path, q20);
  EXPECT_EQ(mismatch.code(), StatusCode::kInvalidArgument) << mismatch.ToString();
  EXPECT_FALSE(HasFrameFigures(*q20));
  EXPECT_EQ(FillFrameFiguresFromEvalJson(work + "/missing.eval.json", q20).code(),
            StatusCode::kNotFound);
  // The check is then the complete record's.
  ComputeDivergence(r);
  EXPECT_TRUE(r.divergence.has_frames);
  EXPECT_EQ(r.divergence.frames_within, 9);
  EXPECT_EQ(r.divergence.worst_frame, 7);
  // Filled points are complete: a second pass has nothing to do.
  EXPECT_EQ(BackfillFrameFigures(r, work), 0);
}

}  // namespace
}  // namespace meshvid
