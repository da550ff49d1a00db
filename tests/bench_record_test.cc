// Bench records (tools/bench/bench_record.h): JSON round trip, files, BD-rate per curve.
#include "tools/bench/bench_record.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "tests/bench_fake_records.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

/// Equal, or both NaN (a figure the point does not hold).
void ExpectSameNumber(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) {
    EXPECT_TRUE(std::isnan(a) && std::isnan(b)) << a << " vs " << b;
  } else {
    EXPECT_EQ(a, b);
  }
}

void ExpectSamePoint(const BenchPoint& a, const BenchPoint& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.codec, b.codec);
  EXPECT_EQ(a.quality, b.quality);
  EXPECT_EQ(a.level, b.level);
  EXPECT_EQ(a.ok, b.ok);
  EXPECT_EQ(a.error, b.error);
  EXPECT_EQ(a.frames, b.frames);
  EXPECT_DOUBLE_EQ(a.bytes_per_frame, b.bytes_per_frame);
  EXPECT_DOUBLE_EQ(a.mbit_per_s, b.mbit_per_s);
  EXPECT_EQ(a.d1_psnr, b.d1_psnr);  // also +inf
  EXPECT_DOUBLE_EQ(a.d2_psnr, b.d2_psnr);
  ExpectSameNumber(a.d1_psnr_mean_of_frames, b.d1_psnr_mean_of_frames);
  ExpectSameNumber(a.d2_psnr_mean_of_frames, b.d2_psnr_mean_of_frames);
  EXPECT_DOUBLE_EQ(a.accuracy_rms, b.accuracy_rms);
  EXPECT_DOUBLE_EQ(a.completeness_rms, b.completeness_rms);
  EXPECT_DOUBLE_EQ(a.coverage, b.coverage);
  EXPECT_DOUBLE_EQ(a.encode_fps, b.encode_fps);
  EXPECT_DOUBLE_EQ(a.decode_fps, b.decode_fps);
  EXPECT_DOUBLE_EQ(a.encode_peak_mb, b.encode_peak_mb);
  EXPECT_DOUBLE_EQ(a.decode_peak_mb, b.decode_peak_mb);
  ASSERT_EQ(a.frame_accuracy_rms.size(), b.frame_accuracy_rms.size());
  for (std::size_t t = 0; t < a.frame_accuracy_rms.size(); ++t) {
    ExpectSameNumber(a.frame_accuracy_rms[t], b.frame_accuracy_rms[t]);
  }
  ASSERT_EQ(a.frame_d1_psnr.size(), b.frame_d1_psnr.size());
  for (std::size_t t = 0; t < a.frame_d1_psnr.size(); ++t) {
    ExpectSameNumber(a.frame_d1_psnr[t], b.frame_d1_psnr[t]);
  }
  EXPECT_EQ(a.commands, b.commands);
}

TEST(BenchRecordTest, JsonRoundTripKeepsEverything) {
  const BenchRecord record = testing::FakeRecord();
  const std::string text = BenchRecordToJson(record);
  EXPECT_NE(text.find("\"d1_psnr\": \"inf\""), std::string::npos);
  EXPECT_NE(text.find("\"d1_psnr_mean_of_frames\": 100.0"), std::string::npos);
  EXPECT_NE(text.find("\"d2_psnr_mean_of_frames\": 71.0"), std::string::npos);
  EXPECT_NE(text.find("\"psnr\": \"d1_psnr_mean_of_frames\""), std::string::npos);
  auto parsed = ParseBenchRecord(text, "fake.json");
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  EXPECT_EQ(parsed->sequence, "fake");
  EXPECT_EQ(parsed->rig, "3-arc");
  EXPECT_EQ(parsed->views, 3);
  EXPECT_EQ(parsed->frames, 10);
  EXPECT_EQ(parsed->run_key, record.run_key);
  EXPECT_EQ(parsed->machine.cpu_model, "Test CPU @ 2.7GHz");
  EXPECT_EQ(parsed->machine.cores, 2);
  EXPECT_DOUBLE_EQ(parsed->simulate_cost.peak_rss_mb, 95);
  EXPECT_DOUBLE_EQ(parsed->baseline_fuse_seconds, 25);
  EXPECT_DOUBLE_EQ(parsed->bench_process_peak_mb, 21);
  EXPECT_EQ(parsed->baseline_command, record.baseline_command);
  ASSERT_EQ(parsed->points.size(), record.points.size());
  for (std::size_t i = 0; i < record.points.size(); ++i) {
    ExpectSamePoint(parsed->points[i], record.points[i]);
  }
  ASSERT_EQ(parsed->encodes.size(), 1u);
  EXPECT_FALSE(parsed->encodes[0].ok);
  EXPECT_EQ(parsed->encodes[0].error, "encode: exit code 1: out of cheese");
  ASSERT_EQ(parsed->bd_rates.size(), record.bd_rates.size());
  // The divergence check.
  EXPECT_TRUE(parsed->divergence.has_frames);
  EXPECT_EQ(parsed->divergence.codec, "av1");
  EXPECT_EQ(parsed->divergence.level, 1);
  EXPECT_EQ(parsed->divergence.baseline_bits, 14);
  EXPECT_EQ(parsed->divergence.frames_within, 9);
  EXPECT_EQ(parsed->divergence.worst_frame, 7);
  EXPECT_DOUBLE_EQ(parsed->divergence.worst_ratio, record.divergence.worst_ratio);
  EXPECT_DOUBLE_EQ(parsed->divergence.share_within, 0.9);
  EXPECT_DOUBLE_EQ(parsed->divergence.ratio_limit, 1.25);
  EXPECT_FALSE(parsed->divergence.share_met);
  EXPECT_DOUBLE_EQ(parsed->divergence.baseline_d1_psnr, 45);
  // Writing the parsed record again gives the same text.
  EXPECT_EQ(BenchRecordToJson(*parsed), text);
}

TEST(BenchRecordTest, PerFrameFiguresAreOneLineEachRoundedToSixDigits) {
  BenchRecord record;
  BenchPoint p;
  p.method = kMethodMeshvid;
  p.codec = "av1";
  p.ok = true;
  p.frames = 4;
  p.frame_accuracy_rms = {0.00123456789, 0.5, 0, std::nan("")};
  p.frame_d1_psnr = {61.23456789, std::numeric_limits<double>::infinity(), 70, 71};
  p.commands = {"meshvid eval --test 'a\"frame_d1_psnr\": [b'"};  // not an array
  EXPECT_TRUE(HasFrameFigures(p));
  record.points.push_back(p);
  const std::string text = BenchRecordToJson(record);
  EXPECT_NE(text.find("\"frame_accuracy_rms\": [0.00123457, 0.5, 0.0, null],\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("\"frame_d1_psnr\": [61.2346, \"inf\", 70.0, 71.0],\n"), std::string::npos)
      << text;
  auto parsed = ParseBenchRecord(text, "p.json");
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  const BenchPoint& q = parsed->points[0];
  ASSERT_EQ(q.frame_accuracy_rms.size(), 4u);
  EXPECT_DOUBLE_EQ(q.frame_accuracy_rms[0], 0.00123457);
  EXPECT_TRUE(std::isnan(q.frame_accuracy_rms[3]));
  EXPECT_TRUE(std::isinf(q.frame_d1_psnr[1]));
  EXPECT_EQ(q.commands, p.commands);
  EXPECT_TRUE(HasFrameFigures(q));
  EXPECT_EQ(BenchRecordToJson(*parsed), text);
  // Figures for another number of frames than the point's are not its per-frame figures.
  p.frames = 5;
  EXPECT_FALSE(HasFrameFigures(p));
  p.frames = 4;
  p.frame_d1_psnr.pop_back();
  EXPECT_FALSE(HasFrameFigures(p));
  EXPECT_FALSE(HasFrameFigures(BenchPoint{}));
  auto bad = ParseBenchRecord(
      "{\"format\": \"meshvid-bench-record/1\", \"points\": [{\"frame_d1_psnr\": 7}]}", "d.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kCorrupt);
}

TEST(BenchRecordTest, RecordsWithoutPerFrameFiguresStillParse) {
  const auto parsed = ParseBenchRecord(testing::RecordJsonWithoutFrameFigures(), "fake.json");
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  ASSERT_EQ(parsed->points.size(), testing::FakeRecord().points.size());
  for (const BenchPoint& p : parsed->points) {
    EXPECT_TRUE(p.frame_accuracy_rms.empty());
    EXPECT_TRUE(p.frame_d1_psnr.empty());
    EXPECT_FALSE(HasFrameFigures(p));
  }
  EXPECT_TRUE(HasMeanOfFramesPsnr(parsed->points[0]));
  // No stored check: an unset one.
  EXPECT_FALSE(parsed->divergence.has_default);
  EXPECT_EQ(parsed->divergence.frames, 0);
  // Written again, the arrays are empty and read back as missing.
  const std::string text = BenchRecordToJson(*parsed);
  EXPECT_NE(text.find("\"frame_accuracy_rms\": []"), std::string::npos);
  const auto reread = ParseBenchRecord(text, "fake.json");
  ASSERT_TRUE(reread.ok());
  EXPECT_FALSE(HasFrameFigures(reread->points[0]));
}

TEST(BenchRecordTest, BdRatesPerCodecAndLevelAgainstTheBaseline) {
  const BenchRecord record = testing::FakeRecord();
  // AV1 levels 0 and 1; FFV1 has one point (no curve).
  ASSERT_EQ(record.bd_rates.size(), 2u);
  const BdRateEntry& level0 = record.bd_rates[0];
  const BdRateEntry& level1 = record.bd_rates[1];
  EXPECT_EQ(level0.codec, "av1");
  EXPECT_EQ(level0.level, 0);
  EXPECT_FALSE(level0.ok);
  EXPECT_NE(level0.note.find("do not overlap"), std::string::npos) << level0.note;
  // Level 0 peaks at 23 dB, 7 dB under the baseline's lowest (30 dB), at 400 kB against 100 kB.
  EXPECT_NE(level0.note.find("meshvid's best point is 7.0 dB below the baseline's lowest, with 4x "
                             "its bytes per frame"),
            std::string::npos)
      << level0.note;
  EXPECT_EQ(level1.level, 1);
  ASSERT_TRUE(level1.ok) << level1.note;
  EXPECT_NEAR(level1.delta, -0.5, 1e-9);
  EXPECT_DOUBLE_EQ(level1.psnr_low, 30);
  EXPECT_DOUBLE_EQ(level1.psnr_high, 45);
}

TEST(BenchRecordTest, BdRateIsOnTheMeanOfFramesPsnr) {
  const BenchRecord record = testing::FakeRecord();
  EXPECT_EQ(RecordPsnrKind(record), kPsnrMeanOfFrames);
  const BdRateEntry& level1 = record.bd_rates[1];
  EXPECT_EQ(level1.psnr, kPsnrMeanOfFrames);
  // On the mean of frames meshvid needs half the bytes at equal PSNR (-50%). On the PSNR of
  // the mean MSE its curve sits 3 dB lower relative to the baseline's (4 dB under its mean of
  // frames against the baseline's 1 dB), so with rate doubling every 5 dB it would read
  // 2^-0.4 - 1 = -24.2%: the figure used must be the mean of frames.
  ASSERT_TRUE(level1.ok);
  EXPECT_NEAR(level1.delta, -0.5, 1e-9);
  BenchRecord on_mean_mse = record;
  for (BenchPoint& p : on_mean_mse.points) p.d1_psnr_mean_of_frames = std::nan("");
  ComputeBdRates(on_mean_mse);
  ASSERT_TRUE(on_mean_mse.bd_rates[1].ok);
  EXPECT_EQ(on_mean_mse.bd_rates[1].psnr, kPsnrOfMeanMse);
  EXPECT_NEAR(on_mean_mse.bd_rates[1].delta, std::pow(2.0, -0.4) - 1, 1e-9);
  // One older point is enough to put the whole record on the PSNR of the mean MSE.
  BenchRecord mixed = record;
  mixed.points[0].d1_psnr_mean_of_frames = std::nan("");
  EXPECT_EQ(RecordPsnrKind(mixed), kPsnrOfMeanMse);
  // A failed point does not count.
  mixed.points[0].ok = false;
  EXPECT_EQ(RecordPsnrKind(mixed), kPsnrMeanOfFrames);
}

TEST(BenchRecordTest, OlderRecordsWithoutTheMeanOfFramesStillParse) {
  const auto parsed = ParseBenchRecord(testing::OlderFakeRecordJson(), "older.json");
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  ASSERT_EQ(parsed->points.size(), testing::FakeRecord().points.size());
  for (const BenchPoint& p : parsed->points) {
    EXPECT_FALSE(HasMeanOfFramesPsnr(p));
    EXPECT_TRUE(std::isnan(p.d2_psnr_mean_of_frames));
  }
  EXPECT_DOUBLE_EQ(parsed->points[0].d1_psnr, 29);  // the old figure is kept
  EXPECT_FALSE(HasFrameFigures(parsed->points[0]));
  EXPECT_EQ(RecordPsnrKind(*parsed), kPsnrOfMeanMse);
  EXPECT_DOUBLE_EQ(D1Psnr(parsed->points[0], RecordPsnrKind(*parsed)), 29);
  // Stored BD-rates without "psnr" were computed on the PSNR of the mean MSE, and say so.
  ASSERT_EQ(parsed->bd_rates.size(), 2u);
  EXPECT_EQ(parsed->bd_rates[1].psnr, kPsnrOfMeanMse);
  EXPECT_NEAR(parsed->bd_rates[1].delta, std::pow(2.0, -0.4) - 1, 1e-9);
  // Recomputing falls back to the same figure and gives the same BD-rates.
  BenchRecord again = *parsed;
  ComputeBdRates(again);
  ASSERT_EQ(again.bd_rates.size(), 2u);
  EXPECT_EQ(again.bd_rates[1].psnr, kPsnrOfMeanMse);
  EXPECT_DOUBLE_EQ(again.bd_rates[1].delta, parsed->bd_rates[1].delta);
  // Written again, the missing figure is null, and reads back as missing.
  const std::string text = BenchRecordToJson(*parsed);
  EXPECT_NE(text.find("\"d1_psnr_mean_of_frames\": null"), std::string::npos);
  const auto reread = ParseBenchRecord(text, "older.json");
  ASSERT_TRUE(reread.ok());
  EXPECT_FALSE(HasMeanOfFramesPsnr(reread->points[0]));
}

TEST(BenchRecordTest, CommittedRecordsParseAndReproduceTheirBdRates) {
  const std::string folder = std::string(MESHVID_GOLDEN_DIR) + "/../../bench/results";
  if (!std::filesystem::is_directory(folder)) GTEST_SKIP() << "no " << folder;
  const auto records = ReadBenchRecords(folder);
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  for (const BenchRecord& record : *records) {
    SCOPED_TRACE(BenchRecordName(record));
    BenchRecord again = record;
    ComputeBdRates(again);
    ASSERT_EQ(again.bd_rates.size(), record.bd_rates.size());
    for (std::size_t i = 0; i < record.bd_rates.size(); ++i) {
      EXPECT_EQ(again.bd_rates[i].psnr, record.bd_rates[i].psnr);
      EXPECT_EQ(again.bd_rates[i].ok, record.bd_rates[i].ok);
      EXPECT_NEAR(again.bd_rates[i].delta, record.bd_rates[i].delta, 1e-9);
    }
  }
}

TEST(BenchRecordTest, FilesAreWrittenAtomicallyAndOtherJsonIsSkipped) {
  testing::TempDir dir;
  BenchRecord record = testing::FakeRecord();
  ASSERT_TRUE(WriteBenchRecord(record, dir.File("fake-3-arc.json")).ok());
  EXPECT_FALSE(std::filesystem::exists(dir.File("fake-3-arc.json.partial")));
  record.sequence = "another";
  ASSERT_TRUE(WriteBenchRecord(record, dir.File("another-3-arc.json")).ok());
  // A Google Benchmark result beside the records is not one of them.
  testing::WriteFile(dir.File("decode.json"), "{\"context\": {}, \"benchmarks\": []}");
  testing::WriteFile(dir.File("notes.txt"), "not json");
  auto records = ReadBenchRecords(dir.path());
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  ASSERT_EQ(records->size(), 2u);
  EXPECT_EQ((*records)[0].sequence, "another");
  EXPECT_EQ((*records)[1].sequence, "fake");

  testing::WriteFile(dir.File("broken.json"),
                     "{\"format\": \"meshvid-bench-record/1\", \"points\": 7");
  records = ReadBenchRecords(dir.path());
  ASSERT_FALSE(records.ok());
  EXPECT_NE(records.status().message().find("broken.json"), std::string::npos);
  ASSERT_TRUE(WriteBenchRecord(record, dir.File("missing/x.json")).ok());  // folder created
  EXPECT_FALSE(WriteBenchRecord(record, dir.File("broken.json/x.json")).ok());  // a file in the way
}

TEST(BenchRecordTest, ParseRejectsWhatIsNotARecord) {
  auto bad = ParseBenchRecord("[1, 2", "a.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kCorrupt);
  bad = ParseBenchRecord("{\"format\": \"something-else\"}", "b.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kUnsupported);
  bad = ParseBenchRecord(
      "{\"format\": \"meshvid-bench-record/1\", \"points\": [{\"d1_psnr\": \"loud\"}]}", "c.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kCorrupt);
  EXPECT_NE(bad.status().message().find("d1_psnr"), std::string::npos);
}

TEST(BenchRecordTest, UpsertReplacesTheSamePoint) {
  BenchRecord record;
  BenchPoint p;
  p.method = kMethodMeshvid;
  p.codec = "hevc";
  p.quality = 40;
  p.level = 2;
  p.error = "first try";
  UpsertPoint(record, p);
  p.ok = true;
  p.error.clear();
  UpsertPoint(record, p);
  p.level = 1;
  UpsertPoint(record, p);
  ASSERT_EQ(record.points.size(), 2u);
  ASSERT_NE(FindPoint(record, kMethodMeshvid, "hevc", 40, 2), nullptr);
  EXPECT_TRUE(FindPoint(record, kMethodMeshvid, "hevc", 40, 2)->ok);
  EXPECT_EQ(FindPoint(record, kMethodMeshvid, "hevc", 40, 3), nullptr);
  BenchEncode e;
  e.method = kMethodMeshvid;
  e.codec = "hevc";
  e.quality = 40;
  UpsertEncode(record, e);
  e.ok = true;
  UpsertEncode(record, e);
  ASSERT_EQ(record.encodes.size(), 1u);
  EXPECT_TRUE(FindEncode(record, kMethodMeshvid, "hevc", 40)->ok);
}

}  // namespace
}  // namespace meshvid
