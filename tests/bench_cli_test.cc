// `meshvid bench`, `meshvid bench-baseline` and `meshvid decode --no-write` end to end (the
// binary path comes from MESHVID_CLI, set by CTest). The full bench needs the encoder and
// takes minutes; its orchestration is tested with a fake executable in bench_runner_test.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "tests/bench_fake_records.h"
#include "tests/test_util.h"
#include "tools/bench/baseline.h"
#include "tools/bench/eval_figures.h"

namespace meshvid {
namespace {

TEST(BenchCliTest, BadArgumentsAreUsageErrorsWithAMessage) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string out = " -o \"" + dir.File("results") + "\" ";
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const Case cases[] = {
      {"bench --sequences nope" + out, 2, "unknown sequence 'nope'"},
      {"bench --sequences cloth --rigs 3-circle" + out, 2, "--rigs '3-circle'"},
      {"bench --sequences cloth --qualities 20,200" + out, 2, "--qualities '20,200'"},
      {"bench --sequences cloth --codecs av1,mpeg2" + out, 2, "--codecs 'av1,mpeg2'"},
      {"bench --sequences cloth --bits 0,8" + out, 2, "--bits '0,8'"},
      {"bench --sequences cloth --samples 10" + out, 2, "--samples must be at least 1000"},
      {"bench --sequences cloth --frames -3" + out, 2, "--frames"},
      {"bench --sequences cloth --encode-args '--quality 20'" + out, 2,
       "--quality is set by the bench itself"},
      {"bench --sequences cloth --report-only" + out, 1, "no bench record"},
      {"bench-baseline x.json -o y --bits 8,99", 2, "--bits '8,99'"},
      {"bench-baseline \"" + dir.File("missing.json") + "\" -o y", 1, "missing.json"},
      {"decode x.mvid", 2, "either -o PATTERN or --no-write"},
      {"decode x.mvid -o f{frame}.ply --no-write", 2, "either -o PATTERN or --no-write"},
  };
  for (const Case& c : cases) {
    const testing::CliRun run = testing::RunMeshvid(c.args, dir);
    const std::string log = run.out + run.err;
    EXPECT_EQ(run.exit_code, c.exit_code) << c.args << "\n" << log;
    EXPECT_NE(log.find(c.message), std::string::npos) << c.args << "\n" << log;
  }
  const testing::CliRun help = testing::RunMeshvid("bench --help", dir);
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--quick"), std::string::npos);
  EXPECT_NE(help.out.find("resumes"), std::string::npos);
  // The baseline step is hidden from the command list.
  const testing::CliRun top = testing::RunMeshvid("--help", dir);
  EXPECT_NE(top.out.find("bench"), std::string::npos);
  EXPECT_EQ(top.out.find("bench-baseline"), std::string::npos);
}

TEST(BenchCliTest, ReportOnlyWritesResultsMarkdownFromRecords) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  std::filesystem::create_directories(dir.File("bench/results"));
  ASSERT_TRUE(
      WriteBenchRecord(testing::FakeRecord(), dir.File("bench/results/fake-3-arc.json")).ok());
  const testing::CliRun run = testing::RunMeshvid(
      "bench --report-only --no-plots -o \"" + dir.File("bench/results") + "\"", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string md = testing::ReadFile(dir.File("bench/RESULTS.md"));
  EXPECT_NE(md.find("| fake | 3-arc | -50.0% (AV1 L1) not met"), std::string::npos) << md;
  EXPECT_NE(md.find("(No plot: plots were not drawn (--no-plots))"), std::string::npos);
  EXPECT_NE(md.find("meshvid bench -o "), std::string::npos);
}

TEST(BenchCliTest, ReportOnlyFillsPerFrameFiguresFromTheEvalJsonInTheWorkFolder) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string results = dir.File("bench/results");
  std::filesystem::create_directories(results + "/tmp/fake-3-arc");
  // Two records written before the per-frame figures; the work folder (OUT/tmp) still holds
  // the eval JSON of fake-3-arc's default point and baseline best, none of fake-6-ring's.
  const std::string older = testing::RecordJsonWithoutFrameFigures();
  testing::WriteFile(results + "/fake-3-arc.json", older);
  std::string ring = older;
  const std::string arc = "\"rig\": \"3-arc\"";
  ring.replace(ring.find(arc), arc.size(), "\"rig\": \"6-ring\"");
  testing::WriteFile(results + "/fake-6-ring.json", ring);
  BenchRecord complete = testing::FakeRecord();
  for (const auto& [method, codec, quality, level] :
       {std::tuple{kMethodMeshvid, "av1", 40, 1}, std::tuple{kMethodBaseline, "draco", 14, -1}}) {
    const BenchPoint* p = FindPoint(complete, method, codec, quality, level);
    ASSERT_NE(p, nullptr);
    testing::WriteFile(EvalJsonPath(results + "/tmp", complete, *p), testing::FakeEvalJson(*p));
  }
  const testing::CliRun run =
      testing::RunMeshvid("bench --report-only --no-plots -o \"" + results + "\"", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("Per-frame figures of 2 point(s) read from their eval JSON"),
            std::string::npos)
      << run.err;
  const std::string md = testing::ReadFile(dir.File("bench/RESULTS.md"));
  EXPECT_NE(md.find("| fake | 3-arc | AV1 q40 L1 | 14 bits | 9/10 (90.0%) missed | 7: 1.55x "
                    "(3.1 vs 2) | 35.00 vs 45.00 dB missed |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| fake | 6-ring | AV1 q40 L1 | 14 bits | n/a (no per-frame figures) | n/a | "
                    "35.00 vs 45.00 dB missed |"),
            std::string::npos)
      << md;
  // The records themselves are left as they were (the next bench run completes them).
  EXPECT_EQ(testing::ReadFile(results + "/fake-3-arc.json"), older);
}

TEST(BenchCliTest, DecodeNoWriteReportsSpeedAndWritesNothing) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string golden = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v1.mvid";
  const testing::CliRun run = testing::RunMeshvid(
      "decode \"" + golden + "\" --level 1 --no-write --json \"" + dir.File("t.json") + "\"", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("frames/s, nothing written"), std::string::npos) << run.err;
  const nlohmann::json j = nlohmann::json::parse(testing::ReadFile(dir.File("t.json")));
  EXPECT_EQ(j.at("level").get<int>(), 1);
  EXPECT_GT(j.at("frames").get<int>(), 0);
  EXPECT_GT(j.at("frames_per_second").get<double>(), 0.0);
  EXPECT_GT(j.at("vertices").get<int>(), 0);
  EXPECT_FALSE(j.at("written").get<bool>());
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 3);  // t.json and the captured stdout/stderr only
}

/// The Y PSNR (eval's, both directions) the baseline's decoded frames of the simulated
/// arm-block at 160x120 must exceed: the fused frames cover only the part the views see, so
/// the ground truth's unseen side takes the nearest seen colour. Measured 20.7 dB.
constexpr double kBaselineColourPsnrFloor = 20.0;

TEST(BenchCliTest, BaselineCodesEveryFrameAtEverySetting) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string cap = dir.File("cap");
  testing::CliRun run = testing::RunMeshvid(
      "simulate scene:arm-block -o \"" + cap + "\" --frames 0:2 --res 160x120 -q", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run =
      testing::RunMeshvid("bench-baseline \"" + cap + "/manifest.json\" -o \"" + dir.File("base") +
                              "\" --bits 8,12 --summary-json \"" + dir.File("s.json") + "\"",
                          dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("Baseline on 2 frames"), std::string::npos) << run.err;
  auto summary = ParseBaselineSummary(testing::ReadFile(dir.File("s.json")), "s.json");
  ASSERT_TRUE(summary.ok()) << summary.status().ToString();
  EXPECT_EQ(summary->frames, 2);
  ASSERT_EQ(summary->settings.size(), 2u);
  EXPECT_EQ(summary->settings[0].position_bits, 8);
  EXPECT_GT(summary->settings[0].bytes_total, 0u);
  // Finer quantisation costs more bytes.
  EXPECT_GT(summary->settings[1].bytes_total, summary->settings[0].bytes_total);
  EXPECT_GT(summary->settings[0].vertices, 0);
  for (const char* f : {"base/b8/f0000.ply", "base/b8/f0001.ply", "base/b12/f0001.ply"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir.File(f))) << f;
  }
  // The bitstreams decode again in a player process of their own.
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.File("base/b8/f0001.drc")));
  run = testing::RunMeshvid(
      "bench-draco-decode \"" + dir.File("base/b12") + "\" --json \"" + dir.File("d.json") + "\"",
      dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json timing = nlohmann::json::parse(testing::ReadFile(dir.File("d.json")));
  EXPECT_EQ(timing.at("frames").get<int>(), 2);
  EXPECT_EQ(timing.at("bytes_total").get<std::size_t>(), summary->settings[1].bytes_total);
  EXPECT_GT(timing.at("frames_per_second").get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(timing.at("vertices").get<double>(), summary->settings[1].vertices);
  run = testing::RunMeshvid("bench-draco-decode \"" + dir.path() + "\"", dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("no .drc file"), std::string::npos) << run.err;
  // The decoded frames are a mesh sequence `meshvid eval` reads.
  run = testing::RunMeshvid("eval --ref \"" + cap + "/ground_truth.obj\" --test \"" +
                                dir.File("base/b12/f{frame:04}.ply") +
                                "\" --samples 2000 --json \"" + dir.File("e.json") + "\" -q",
                            dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("mean"), std::string::npos);
  // The bench reads the per-frame figures of meshvid eval's JSON.
  auto figures = ParseEvalFigures(testing::ReadFile(dir.File("e.json")), "e.json");
  ASSERT_TRUE(figures.ok()) << figures.status().ToString();
  EXPECT_EQ(figures->frames, 2);
  ASSERT_EQ(figures->frame_accuracy_rms.size(), 2u);
  ASSERT_EQ(figures->frame_d1_psnr.size(), 2u);
  for (int t = 0; t < 2; ++t) {
    EXPECT_GT(figures->frame_accuracy_rms[t], 0.0);
    EXPECT_TRUE(std::isfinite(figures->frame_d1_psnr[t]));
  }
  EXPECT_TRUE(std::isfinite(figures->d1_psnr_mean_of_frames));
  // The simulated capture has colour: every coded mesh carries the views' colour per vertex,
  // its bytes counted apart, and the decoded frames are evaluated for colour too.
  for (const BaselineSetting& s : summary->settings) {
    EXPECT_GT(s.colour_bytes_total, 0u);
    EXPECT_LT(s.colour_bytes_total, s.bytes_total);
  }
  EXPECT_GT(figures->y_psnr, kBaselineColourPsnrFloor);
  EXPECT_TRUE(std::isfinite(figures->yuv_psnr));
  run = testing::RunMeshvid("bench-baseline \"" + cap + "/manifest.json\" -o \"" +
                                dir.File("grey") + "\" --bits 12 --no-colour --json \"" +
                                dir.File("grey.json") + "\" -q",
                            dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  auto grey = ParseBaselineSummary(testing::ReadFile(dir.File("grey.json")), "grey.json");
  ASSERT_TRUE(grey.ok()) << grey.status().ToString();
  EXPECT_EQ(grey->settings[0].colour_bytes_total, 0u);
  EXPECT_EQ(grey->settings[0].bytes_total,
            summary->settings[1].bytes_total - summary->settings[1].colour_bytes_total);

  // Decimated to a vertex budget, as a per-frame player streams it: fewer vertices, fewer bytes.
  run = testing::RunMeshvid("bench-baseline \"" + cap + "/manifest.json\" -o \"" +
                                dir.File("small") + "\" --decimate 300 --bits 12 --json \"" +
                                dir.File("small.json") + "\" -q",
                            dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  auto small = ParseBaselineSummary(testing::ReadFile(dir.File("small.json")), "small.json");
  ASSERT_TRUE(small.ok()) << small.status().ToString();
  ASSERT_EQ(small->settings.size(), 1u);
  EXPECT_EQ(small->settings[0].target_vertices, 300u);
  EXPECT_LE(small->settings[0].vertices, 300);
  EXPECT_GT(small->settings[0].vertices, 200);
  EXPECT_LT(small->settings[0].bytes_total, summary->settings[1].bytes_total);
  // The decimated mesh is coloured too, with fewer vertices to colour.
  EXPECT_GT(small->settings[0].colour_bytes_total, 0u);
  EXPECT_LT(small->settings[0].colour_bytes_total, summary->settings[1].colour_bytes_total);
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.File("small/v300-b12/f0001.ply")));
  run = testing::RunMeshvid(
      "bench-baseline \"" + cap + "/manifest.json\" -o \"" + dir.File("bad") + "\" --decimate 2 -q",
      dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--decimate"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace meshvid
