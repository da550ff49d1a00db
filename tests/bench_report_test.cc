// RESULTS.md and RD plots (tools/bench/bench_report.h) from a small fake record set.
#include "tools/bench/bench_report.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/bench_fake_records.h"
#include "tests/test_util.h"
#include "tools/bench/child_process.h"

namespace meshvid {
namespace {

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

ReportOptions FakeOptions() {
  ReportOptions options;
  options.date = "2026-11-22T11:00:00Z";
  options.command_line = "meshvid bench --quick -o bench/results";
  options.plots["fake-3-arc"] = "results/fake-3-arc-rd.png";
  options.stills["fake-3-arc"] = "results/fake-3-arc-still.png";
  return options;
}

TEST(BenchReportTest, ResultsMarkdownHasTablesGoalCommandsAndMachine) {
  BenchRecord failed_sim;
  failed_sim.sequence = "broken";
  failed_sim.rig = "6-ring";
  failed_sim.simulate_error = "exit code 1: no such file";
  const std::vector<BenchRecord> records = {testing::FakeRecord(), failed_sim};
  const std::string md = GenerateResultsMarkdown(records, FakeOptions());
  EXPECT_TRUE(Contains(md, "# meshvid bench: results")) << md;
  EXPECT_TRUE(Contains(md, "on 2026-11-22T11:00:00Z"));
  EXPECT_TRUE(Contains(md, "    meshvid bench --quick -o bench/results\n"));
  EXPECT_TRUE(Contains(md, "Test CPU @ 2.7GHz, 2 cores, 24.0 GB RAM, Linux 6.1 x86_64"));
  // Goal: best BD-rate -50% (not met), none against a decimated baseline (the fake record has
  // none), decode 600/30 = 20x (met), coverage 95% vs 90% (met).
  EXPECT_TRUE(Contains(
      md, "| fake | 3-arc | -50.0% (AV1 L1) not met | n/a | 20.0x met | 95.0% vs 90.0% met |"))
      << md;
  EXPECT_TRUE(Contains(md, "| broken | 6-ring | simulation failed | | | |"));
  // The still of the default point's worst frame, beside the RD plot.
  EXPECT_TRUE(Contains(md, "![worst frame, fake-3-arc](results/fake-3-arc-still.png)")) << md;
  EXPECT_EQ(BenchStillName(records[0]), "fake-3-arc-still.png");
  EXPECT_TRUE(Contains(md, "(peak memory floor: the bench process's own 21 MB)"));
  EXPECT_TRUE(Contains(md, "**Simulation failed**, nothing else ran: exit code 1: no such file"));
  // The BD-rate table: a value with its interval, and the reason where there is none.
  // The BD-rate table names the D1 PSNR it is computed on.
  EXPECT_TRUE(
      Contains(md, "| reference | codec | level | BD-rate | D1 PSNR | over D1 PSNR | note |"));
  EXPECT_TRUE(
      Contains(md, "| baseline | AV1 | 1 | **-50.0%** | mean of frames | 30.00 - 45.00 dB |  |"))
      << md;
  EXPECT_TRUE(Contains(
      md, "| baseline | AV1 | 0 | n/a | mean of frames |  | the PSNR ranges do not overlap"));
  // Point rows: the baseline first, both averages of D1 and D2, PSNR inf printed as such.
  EXPECT_TRUE(Contains(md,
                       "| Mbit/s | D1 PSNR, mean of frames | D1 PSNR, mean MSE | "
                       "D2 PSNR, mean of frames | D2 PSNR, mean MSE |"));
  EXPECT_TRUE(Contains(md,
                       "| baseline | DRACO | 8 bits | - | 100000 | 20 | 30.00 | 29.00 | 34.00 | "
                       "33.00 | 2 | 4 | 90.0% | 0.4 | 30 | 250 | 250 |"))
      << md;
  EXPECT_TRUE(Contains(md, "| meshvid | AV1 | q20 | 1 | 50000 | 10 | 30.00 | 26.00 |"));
  EXPECT_TRUE(
      Contains(md, "| meshvid | FFV1 | q100 | 1 | 900000 | 180 | 100.00 | inf | 71.00 | 70.00 |"));
  EXPECT_LT(md.find("| baseline | DRACO | 8 bits"), md.find("| meshvid | AV1 | q20 | 1"));
  EXPECT_TRUE(Contains(md, "![D1 PSNR, mean of frames, against rate, fake-3-arc]"
                           "(results/fake-3-arc-rd.png)"));
  // How both averages are measured, and which one BD-rate uses.
  EXPECT_TRUE(Contains(md, "**mean of frames**, the mean of the per-frame PSNRs"));
  EXPECT_TRUE(Contains(md, "**mean MSE**, the PSNR of the mean MSE over frames"));
  EXPECT_TRUE(Contains(
      md, "against the baseline and against each decimated curve, on D1 PSNR, mean of frames"));
  EXPECT_FALSE(Contains(md, "This record predates"));
  EXPECT_TRUE(Contains(md, "- hevc q40: encode: exit code 1: out of cheese"));
  EXPECT_TRUE(
      Contains(md, "meshvid simulate scene:fake -o work/fake-3-arc/capture --views 3 -q\n"));
  EXPECT_TRUE(Contains(md, "meshvid decode av1-q20.mvid --level 1 --no-write -q\n"));
  // Only the first file's decode commands are listed; every encode is.
  EXPECT_FALSE(Contains(md, "meshvid decode av1-q40.mvid"));
  EXPECT_TRUE(Contains(md, "meshvid encode c -o hevc-q40.mvid --codec hevc -q\n"));
  // Deterministic.
  EXPECT_EQ(md, GenerateResultsMarkdown(records, FakeOptions()));
}

TEST(BenchReportTest, DivergenceTableHasOneRowPerRecord) {
  BenchRecord failed_sim;
  failed_sim.sequence = "broken";
  failed_sim.rig = "6-ring";
  BenchRecord met = testing::FakeRecord();
  met.rig = "6-ring";
  BenchPoint* m = FindPoint(met, kMethodMeshvid, "av1", 40, 1);
  ASSERT_NE(m, nullptr);
  m->frame_accuracy_rms.assign(10, 0.0021);
  m->frame_accuracy_rms[3] = 0.0024;
  m->d1_psnr_mean_of_frames = 45.5;
  auto no_frames = ParseBenchRecord(testing::RecordJsonWithoutFrameFigures(), "fake.json");
  ASSERT_TRUE(no_frames.ok());
  no_frames->sequence = "older";
  const std::vector<BenchRecord> records = {testing::FakeRecord(), met, *no_frames, failed_sim};
  const std::string md = GenerateResultsMarkdown(records, FakeOptions());
  EXPECT_TRUE(Contains(md,
                       "## Divergence\n\nmeshvid at the encoder's default settings (AV1, "
                       "quality 40, decoded at the finest level its file stores)"))
      << md;
  EXPECT_TRUE(Contains(md, "Goals: the ratio is at most 1.25 on at least 95% of the frames"));
  EXPECT_TRUE(Contains(md,
                       "| sequence | rig | default point | baseline best | frames within 1.25x | "
                       "worst frame: ratio (meshvid vs baseline accuracy) | D1 PSNR, mean of "
                       "frames: default vs baseline best |"));
  // FakeRecord: 9 of 10 frames within 1.25x, frame 7 at 1.55x (3.1 against 2 mm), 35 against
  // 45 dB.
  EXPECT_TRUE(Contains(md,
                       "| fake | 3-arc | AV1 q40 L1 | 14 bits | 9/10 (90.0%) missed | "
                       "7: 1.55x (3.1 vs 2) | 35.00 vs 45.00 dB missed |"))
      << md;
  EXPECT_TRUE(Contains(md,
                       "| fake | 6-ring | AV1 q40 L1 | 14 bits | 10/10 (100.0%) met | "
                       "3: 1.2x (2.4 vs 2) | 45.50 vs 45.00 dB met |"))
      << md;
  // A record without per-frame figures still compares the D1 PSNRs, and says why not more.
  EXPECT_TRUE(Contains(md,
                       "| older | 3-arc | AV1 q40 L1 | 14 bits | n/a (no per-frame "
                       "figures) | n/a | 35.00 vs 45.00 dB missed |"))
      << md;
  EXPECT_TRUE(Contains(md, "- older 3-arc: no per-frame figures for the default point"));
  EXPECT_TRUE(Contains(md, "| broken | 6-ring | simulation failed | | | | |"));
  // After the goal table, before the records' sections.
  EXPECT_LT(md.find("## Against the goal"), md.find("## Divergence"));
  EXPECT_LT(md.find("## Divergence"), md.find("## fake, 3 views"));
  // A record without the default point.
  BenchRecord no_default = testing::FakeRecord();
  for (BenchPoint& p : no_default.points) p.quality = p.quality == 40 ? 45 : p.quality;
  const std::string md2 = GenerateResultsMarkdown({no_default}, FakeOptions());
  EXPECT_TRUE(Contains(md2, "| fake | 3-arc | AV1 q40 (n/a) | 14 bits | n/a | n/a | n/a |")) << md2;
  EXPECT_TRUE(Contains(md2, "- fake 3-arc: no av1 q40 point"));
}

TEST(BenchReportTest, ColourTableComparesTheDefaultPointWithTheBaselineBest) {
  BenchRecord coloured = testing::FakeRecord();
  coloured.rig = "6-ring";
  BenchPoint* m = FindPoint(coloured, kMethodMeshvid, "av1", 40, 1);      // 100000 bytes/frame
  BenchPoint* b = FindPoint(coloured, kMethodBaseline, "draco", 14, -1);  // the best D1
  ASSERT_TRUE(m != nullptr && b != nullptr);
  m->y_psnr = 32.5;
  m->yuv_psnr = 34;
  m->colour_bytes_per_frame = 30000;
  b->y_psnr = 33;
  b->yuv_psnr = 35;
  b->colour_bytes_per_frame = 200000;
  BenchRecord failed_sim;
  failed_sim.sequence = "broken";
  failed_sim.rig = "6-ring";
  const std::string md =
      GenerateResultsMarkdown({testing::FakeRecord(), coloured, failed_sim}, FakeOptions());
  EXPECT_TRUE(Contains(md, "## Colour\n\nThe default point's colour")) << md;
  EXPECT_TRUE(Contains(md,
                       "Goals (issue 44): Y PSNR within 1 dB of the baseline's, at most "
                       "0.2x its colour bytes, colour at most 40% of meshvid's file."));
  // -0.5 dB, 0.15x the colour bytes, colour 30% of the file: every goal met.
  EXPECT_TRUE(Contains(md,
                       "| fake | 6-ring | 32.50 vs 33.00 dB (-0.50) met | 30000 vs 200000 | "
                       "0.15x met | 30.0% met | 34.00 vs 35.00 dB |"))
      << md;
  EXPECT_TRUE(Contains(md, "| fake | 3-arc | n/a (no colour measured) | | | | |"));
  EXPECT_TRUE(Contains(md, "| broken | 6-ring | simulation failed | | | | |"));
  EXPECT_LT(md.find("## Divergence"), md.find("## Colour"));
  EXPECT_LT(md.find("## Colour"), md.find("## fake, 3 views"));
  // Each point's row ends with its colour bytes and Y PSNR ("-" where not measured).
  EXPECT_TRUE(Contains(md, "| encode MB | decode MB | colour bytes/frame | Y PSNR |"));
  EXPECT_TRUE(Contains(md, "| 400 | 60 | 30000 | 32.50 |")) << md;
  EXPECT_TRUE(Contains(md, "| 250 | 250 | - | - |"));
}

TEST(BenchReportTest, AnOlderRecordFallsBackToTheMeanMseAndSaysSo) {
  const auto older = ParseBenchRecord(testing::OlderFakeRecordJson(), "fake-3-arc.json");
  ASSERT_TRUE(older.ok()) << older.status().ToString();
  const std::string md = GenerateResultsMarkdown({*older}, FakeOptions());
  EXPECT_TRUE(Contains(md, "| AV1 | 1 | **-24.2%** | mean MSE (older record) | 29.00 - 41.00 dB |"))
      << md;
  EXPECT_TRUE(Contains(md, "| baseline | DRACO | 8 bits | - | 100000 | 20 | n/a | 29.00 | n/a | "
                           "33.00 |"));
  EXPECT_TRUE(Contains(md, "This record predates the mean of per-frame PSNRs"));
  EXPECT_TRUE(Contains(md, "![D1 PSNR, mean MSE (older record), against rate, fake-3-arc]"));
  // Its divergence check compares the PSNRs of the mean MSE, and says so.
  EXPECT_TRUE(Contains(md, "| 31.00 vs 44.00 dB (mean MSE, older record) missed |")) << md;
  // Its plot is on the same figure as its BD-rates.
  const std::string script = RdPlotScript(*older, "fake-3-arc-rd.png");
  EXPECT_TRUE(Contains(script, "set ylabel \"D1 PSNR, of the mean MSE (dB)\""));
  EXPECT_TRUE(Contains(script, "$s0 << EOD\n20 29.0000\n40 34.0000\n")) << script;
  // The lossless point has PSNR inf there: not drawable, so no FFV1 curve.
  EXPECT_FALSE(Contains(script, "FFV1"));
}

TEST(BenchReportTest, MissingPlotsAreExplained) {
  ReportOptions options = FakeOptions();
  options.plots.clear();
  options.stills.clear();
  options.plot_note = "gnuplot is not installed";
  const std::string md = GenerateResultsMarkdown({testing::FakeRecord()}, options);
  EXPECT_TRUE(Contains(md, "(No plot: gnuplot is not installed)"));
  EXPECT_FALSE(Contains(md, "!["));
}

TEST(BenchReportTest, PlotScriptHasEveryCurve) {
  const std::string script = RdPlotScript(testing::FakeRecord(), "fake-3-arc-rd.png");
  EXPECT_TRUE(Contains(script, "set output \"fake-3-arc-rd.png\""));
  EXPECT_TRUE(Contains(script, "set logscale x"));
  EXPECT_TRUE(Contains(script, "title \"baseline: per-frame fusion + Draco\""));
  EXPECT_TRUE(Contains(script, "title \"meshvid AV1 L1\""));
  EXPECT_TRUE(Contains(script, "title \"meshvid AV1 L0\""));
  EXPECT_TRUE(Contains(script, "set ylabel \"D1 PSNR, mean of frames (dB)\""));
  // The lossless point: exact frames, capped at 100 dB in the mean of frames, so drawable.
  EXPECT_TRUE(Contains(script, "title \"meshvid FFV1 L1 (lossless)\""));
  EXPECT_TRUE(Contains(script, "180 100.0000\n"));
  // The baseline's data: Mbit/s and D1 PSNR (mean of frames), sorted by rate.
  EXPECT_TRUE(
      Contains(script, "$s0 << EOD\n20 30.0000\n40 35.0000\n80 40.0000\n160 45.0000\nEOD\n"))
      << script;
  EXPECT_EQ(RdPlotScript(BenchRecord{}, "x.png"), "");
}

TEST(BenchReportTest, PlotsAreDrawnWithGnuplotOrSkippedWithAMessage) {
  testing::TempDir dir;
  const std::vector<BenchRecord> records = {testing::FakeRecord()};
  const std::string saved_path = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", dir.path().c_str(), 1);  // no gnuplot here
  auto skipped = RenderRdPlots(records, dir.path(), dir.File("logs"));
  setenv("PATH", saved_path.c_str(), 1);
  ASSERT_FALSE(skipped.ok());
  EXPECT_EQ(skipped.status().code(), StatusCode::kNotFound);
  EXPECT_TRUE(Contains(skipped.status().message(), "gnuplot-nox"));
  EXPECT_FALSE(std::filesystem::exists(dir.File("fake-3-arc.gp")));

  if (FindProgram("gnuplot").empty()) GTEST_SKIP() << "gnuplot is not installed";
  auto plots = RenderRdPlots(records, dir.path(), dir.File("logs"));
  ASSERT_TRUE(plots.ok()) << plots.status().ToString();
  ASSERT_EQ(plots->count("fake-3-arc"), 1u);
  EXPECT_EQ(plots->at("fake-3-arc"), "fake-3-arc-rd.png");
  EXPECT_TRUE(std::filesystem::exists(dir.File("fake-3-arc.gp")));
  const std::string png = testing::ReadFile(dir.File("fake-3-arc-rd.png"));
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(BenchReportTest, MachineInfoIsRead) {
  const MachineInfo machine = ReadMachineInfo();
  EXPECT_GT(machine.cores, 0);
  EXPECT_GT(machine.ram_gb, 0.0);
  EXPECT_FALSE(machine.kernel.empty());
}

}  // namespace
}  // namespace meshvid
