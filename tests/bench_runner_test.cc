// The bench orchestration (tools/bench/bench_runner.h) against a fake `meshvid` (a shell
// script answering simulate, bench-baseline, encode, info, decode and eval like the real one),
// so resuming and failure recording are tested in milliseconds; and the child processes.
#include "tools/bench/bench_runner.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/test_util.h"
#include "tools/bench/bench_report.h"
#include "tools/bench/child_process.h"

namespace meshvid {
namespace {

/// Appends its arguments to calls.txt beside itself. encode fails for --quality 66. eval gives
/// two frames of accuracy RMS 0.001, but 0.002 on frame 1 of a .mvid, and colour. A .mvid's
/// colour is a tenth of its bytes, the baseline's 100 bytes per position bit.
constexpr const char* kFakeMeshvid = R"SH(#!/bin/sh
here=$(dirname "$0")
echo "$*" >> "$here/calls.txt"
cmd=$1; shift
if [ "$cmd" = info ]; then
  q=$(cat "$1")
  echo "{\"levels\": 1, \"frames\": 2, \"bytes\": {\"file\": $((q * 100)), \"colour\": $((q * 10))}}"
  exit 0
fi
out=; json=; summary=; quality=0; level=0; test=; bits=; decimate=0
while [ $# -gt 0 ]; do
  case "$1" in
    -o) out=$2; shift ;;
    --json) json=$2; shift ;;
    --summary-json) summary=$2; shift ;;
    --quality) quality=$2; shift ;;
    --level) level=$2; shift ;;
    --test) test=$2; shift ;;
    --bits) bits=$2; shift ;;
    --decimate) decimate=$2; shift ;;
    --ref|--codec|--views|--layout|--frames|--samples|--azimuth) shift ;;
    -*) ;;
  esac
  shift
done
case $cmd in
  simulate)
    mkdir -p "$out" && touch "$out/f0_v0.ply" "$out/f1_v0.ply" "$out/ground_truth.obj"
    echo '{"format": "meshvid-capture", "version": 1, "frame_rate": 50, "views": [{"name": "v0"}],
           "frames": [["f0_v0.ply"], ["f1_v0.ply"]]}' > "$out/manifest.json" ;;
  bench-baseline)
    settings=
    for n in $(echo "$decimate" | tr ',' ' '); do
      for b in $(echo "$bits" | tr ',' ' '); do
        dir=b$b; vertices=100; bytes=$((b * 1000))
        if [ "$n" != 0 ]; then dir=v$n-b$b; vertices=$n; bytes=$((b * n)); fi
        mkdir -p "$out/$dir" && touch "$out/$dir/f0000.ply"
        [ -n "$settings" ] && settings="$settings,"
        settings="$settings{\"position_bits\": $b, \"target_vertices\": $n,
          \"bytes_total\": $bytes, \"colour_bytes_total\": $((b * 100)),
          \"encode_seconds\": 0.5, \"decode_seconds\": 0.1,
          \"vertices\": $vertices, \"triangles\": 200,
          \"pattern\": \"$out/$dir/f{frame:04}.ply\"}"
      done
    done
    echo "{\"frames\": 2, \"frame_rate\": 50, \"load_seconds\": 0.5, \"fuse_seconds\": 1.0,
           \"settings\": [$settings]}" > "$summary" ;;
  encode)
    if [ "$quality" = 66 ]; then echo "encoder exploded" >&2; exit 1; fi
    echo "$quality" > "$out" ;;
  decode)
    echo '{"frames_per_second": 500, "vertices": 1000}' > "$json" ;;
  bench-draco-decode)
    echo '{"frames_per_second": 20}' > "$json" ;;
  eval)
    case "$test" in
      *.mvid) psnr=$((30 + $(cat "$test") / 10 + level)); last=0.002 ;;
      *) psnr=$(echo "$test" | sed 's|.*b\([0-9]*\)/f.*|\1|'); psnr=$((psnr * 3)); last=0.001 ;;
    esac
    echo "{\"mean\": {\"d1_psnr\": $psnr, \"d2_psnr\": \"inf\",
           \"d1_psnr_mean_of_frames\": $((psnr + 2)), \"d2_psnr_mean_of_frames\": 100,
           \"accuracy_rms\": 0.001,
           \"completeness_rms\": 0.002, \"hausdorff\": 0.01, \"coverage\": 0.9,
           \"y_psnr\": 33.5, \"yuv_psnr\": 35.5},
           \"frames\": [{\"frame\": 0, \"d1_psnr\": $psnr, \"accuracy_rms\": 0.001},
                      {\"frame\": 1, \"d1_psnr\": \"inf\", \"accuracy_rms\": $last}]}" \
      > "$json" ;;
  *) echo "unknown command $cmd" >&2; exit 2 ;;
esac
)SH";

struct FakeBench {
  testing::TempDir dir;
  BenchOptions options;
  std::vector<std::string> log;
  BenchEvents events;

  FakeBench() {
    const std::string fake = dir.File("meshvid");
    testing::WriteFile(fake, kFakeMeshvid);
    chmod(fake.c_str(), 0755);
    options.meshvid = fake;
    options.sequences = {{"fake", "scene:fake", 0}};
    options.rigs = {{3, "arc"}};
    options.codecs = {"av1"};
    options.qualities = {40, 66, 80};
    options.position_bits = {10, 14};
    options.decimated_bits = {};  // its own test turns it on
    options.eval_samples = 1000;
    options.results_dir = dir.File("results");
    options.work_dir = dir.File("work");
    // The call counts below leave out the still (its own test turns it on).
    options.draw_stills = false;
    events.log = [this](const std::string& line) { log.push_back(line); };
  }
  std::vector<std::string> Calls() const {
    std::vector<std::string> calls;
    std::istringstream in(testing::ReadFile(dir.File("calls.txt")));
    for (std::string line; std::getline(in, line);) calls.push_back(line);
    return calls;
  }
};

TEST(BenchRunnerTest, RecordsPointsAndFailuresThenResumesOnlyWhatFailed) {
  FakeBench bench;
  auto records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  ASSERT_EQ(records->size(), 1u);
  // A copy: `records` is assigned again below (a reference would dangle; ASan caught it).
  const BenchRecord r = (*records)[0];
  EXPECT_TRUE(r.simulate_ok) << r.simulate_error;
  EXPECT_EQ(r.frames, 2);
  EXPECT_DOUBLE_EQ(r.frame_rate, 50);
  EXPECT_TRUE(r.baseline_ok) << r.baseline_error;
  // 2 baseline points, (40, 80) x levels 0..1 and the lossless point x 2 levels.
  EXPECT_EQ(r.points.size(), 2u + 4u + 2u);
  for (const BenchPoint& p : r.points) EXPECT_TRUE(p.ok) << p.codec << p.quality << ": " << p.error;
  BenchRecord copy = r;
  const BenchPoint* b10 = FindPoint(copy, kMethodBaseline, "draco", 10, -1);
  ASSERT_NE(b10, nullptr);
  EXPECT_DOUBLE_EQ(b10->bytes_per_frame, 5000);
  EXPECT_DOUBLE_EQ(b10->mbit_per_s, 5000 * 8 * 50 / 1e6);
  EXPECT_DOUBLE_EQ(b10->d1_psnr, 30);
  EXPECT_DOUBLE_EQ(b10->d1_psnr_mean_of_frames, 32);
  EXPECT_DOUBLE_EQ(b10->d2_psnr_mean_of_frames, 100);
  EXPECT_DOUBLE_EQ(b10->decode_fps, 20);  // from bench-draco-decode
  EXPECT_GT(b10->decode_peak_mb, 0);
  ASSERT_EQ(b10->commands.size(), 3u);  // baseline, Draco decoding, eval
  EXPECT_EQ(b10->commands[1].rfind("meshvid bench-draco-decode ", 0), 0u) << b10->commands[1];
  EXPECT_DOUBLE_EQ(b10->encode_fps, 2 / 2.0);  // 2 frames / (0.5 + 1.0 + 0.5) s
  EXPECT_TRUE(std::isinf(b10->d2_psnr));
  // Colour: the eval's Y and YUV PSNR, the summary's colour bytes.
  EXPECT_DOUBLE_EQ(b10->y_psnr, 33.5);
  EXPECT_DOUBLE_EQ(b10->yuv_psnr, 35.5);
  EXPECT_DOUBLE_EQ(b10->colour_bytes_per_frame, 500);  // 1000 bytes, 2 frames
  const BenchPoint* h80 = FindPoint(copy, kMethodMeshvid, "av1", 80, 1);
  ASSERT_NE(h80, nullptr);
  EXPECT_DOUBLE_EQ(h80->bytes_per_frame, 4000);  // 8000-byte file, 2 frames
  EXPECT_DOUBLE_EQ(h80->d1_psnr, 39);
  EXPECT_DOUBLE_EQ(h80->colour_bytes_per_frame, 400);  // info's 800 colour bytes, 2 frames
  EXPECT_DOUBLE_EQ(h80->y_psnr, 33.5);
  EXPECT_DOUBLE_EQ(h80->decode_fps, 500);
  EXPECT_GT(h80->encode_peak_mb, 0);
  ASSERT_EQ(h80->commands.size(), 3u);
  EXPECT_EQ(h80->commands[1].rfind("meshvid decode ", 0), 0u) << h80->commands[1];
  // Per-frame figures from the eval JSON.
  EXPECT_EQ(h80->frame_accuracy_rms, (std::vector<double>{0.001, 0.002}));
  ASSERT_EQ(h80->frame_d1_psnr.size(), 2u);
  EXPECT_DOUBLE_EQ(h80->frame_d1_psnr[0], 39);
  EXPECT_TRUE(std::isinf(h80->frame_d1_psnr[1]));
  EXPECT_EQ(b10->frame_accuracy_rms, (std::vector<double>{0.001, 0.001}));
  // The divergence check: AV1 q40 at level 1 (the file's finest) against 14 bits (44 dB, the
  // baseline's highest): frame 1 at 2x, 37 against 44 dB.
  const DivergenceCheck& d = r.divergence;
  EXPECT_TRUE(d.has_default && d.has_baseline && d.has_frames) << d.note;
  EXPECT_EQ(d.quality, 40);
  EXPECT_EQ(d.level, 1);
  EXPECT_EQ(d.baseline_bits, 14);
  EXPECT_EQ(d.frames, 2);
  EXPECT_EQ(d.frames_within, 1);
  EXPECT_EQ(d.worst_frame, 1);
  EXPECT_DOUBLE_EQ(d.worst_ratio, 2);
  EXPECT_DOUBLE_EQ(d.meshvid_d1_psnr, 37);
  EXPECT_DOUBLE_EQ(d.baseline_d1_psnr, 44);
  EXPECT_FALSE(d.psnr_met);
  const BenchEncode* failed = FindEncode(copy, kMethodMeshvid, "av1", 66);
  ASSERT_NE(failed, nullptr);
  EXPECT_FALSE(failed->ok);
  EXPECT_NE(failed->error.find("encoder exploded"), std::string::npos) << failed->error;
  ASSERT_EQ(r.bd_rates.size(), 2u);  // av1 levels 0 and 1 (ffv1: one point)
  EXPECT_EQ(r.bd_rates[0].psnr, kPsnrMeanOfFrames);
  bool logged_failure = false;
  for (const std::string& line : bench.log)
    logged_failure |= line.find("q66 FAILED") != std::string::npos;
  EXPECT_TRUE(logged_failure);
  // The record on disk is what was returned; the baseline's decoded frames are gone.
  auto saved = ReadBenchRecord(bench.options.results_dir + "/fake-3-arc.json");
  ASSERT_TRUE(saved.ok()) << saved.status().ToString();
  EXPECT_EQ(saved->points.size(), r.points.size());
  EXPECT_EQ(saved->divergence.frames_within, 1);
  EXPECT_FALSE(std::filesystem::exists(bench.options.work_dir + "/fake-3-arc/baseline/b10"));

  // Again: only the failed encode is retried.
  const std::size_t calls = bench.Calls().size();
  records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok());
  const std::vector<std::string> after = bench.Calls();
  ASSERT_EQ(after.size(), calls + 1);
  EXPECT_EQ(after.back().rfind("encode ", 0), 0u);
  EXPECT_NE(after.back().find("--quality 66"), std::string::npos);
  EXPECT_EQ((*records)[0].points.size(), r.points.size());

  // Other settings: the record is not reused.
  bench.options.frames = 1;
  records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok());
  EXPECT_GT(bench.Calls().size(), after.size() + 10);
}

TEST(BenchRunnerTest, DecimatedBaselineIsSizedByTheDefaultPointAndGetsItsOwnBdRates) {
  FakeBench bench;
  bench.options.decimated_bits = {8, 12};
  auto records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  BenchRecord r = (*records)[0];
  // The default point (AV1 q40 at its finest level) decodes 1000 vertices a frame.
  std::string decimate_call;
  for (const std::string& call : bench.Calls()) {
    if (call.find("--decimate") != std::string::npos) decimate_call = call;
  }
  EXPECT_NE(decimate_call.find("--decimate 500,1000,2000 --bits 8,12"), std::string::npos)
      << decimate_call;
  for (double multiple : kDecimatedMultiples) {
    for (int bits : {8, 12}) {
      const BenchPoint* p = FindPoint(r, kMethodDecimated, DecimatedCodecName(multiple), bits, -1);
      ASSERT_NE(p, nullptr) << multiple << "x " << bits;
      EXPECT_TRUE(p->ok) << p->error;
      EXPECT_DOUBLE_EQ(p->vertices, 1000 * multiple);
      EXPECT_DOUBLE_EQ(p->bytes_per_frame, bits * 1000 * multiple / 2);
      EXPECT_DOUBLE_EQ(p->d1_psnr, 3 * bits);
      const BenchEncode* e = FindEncode(r, kMethodDecimated, DecimatedCodecName(multiple), bits);
      ASSERT_NE(e, nullptr);
      EXPECT_DOUBLE_EQ(e->target_vertices, 1000 * multiple);
    }
  }
  // BD-rates of each meshvid curve (AV1 levels 0 and 1) against the full baseline, then
  // against each decimated curve.
  std::vector<std::string> references;
  for (const BdRateEntry& b : r.bd_rates) {
    if (b.level == 1) references.push_back(b.reference);
  }
  EXPECT_EQ(references, (std::vector<std::string>{"baseline", "decimated draco 0.5x",
                                                  "decimated draco 1x", "decimated draco 2x"}));
  // The decoded frames are removed once measured; the report names the decimated points.
  EXPECT_FALSE(std::filesystem::exists(bench.options.work_dir + "/fake-3-arc/decimated/v1000-b8"));
  const std::string md = GenerateResultsMarkdown({r}, ReportOptions{});
  EXPECT_NE(md.find("| decimated | DRACO 1X | 8 bits, 1000 vertices |"), std::string::npos);
  EXPECT_NE(md.find("| decimated draco 1x | AV1 | 1 |"), std::string::npos);

  // Again: nothing is run again.
  const std::size_t calls = bench.Calls().size();
  records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok());
  EXPECT_EQ(bench.Calls().size(), calls + 1);  // the encode of q66, which fails every time
}

TEST(BenchRunnerTest, PointsOfAnOlderRecordAreMeasuredAgain) {
  FakeBench bench;
  ASSERT_TRUE(RunBench(bench.options, bench.events).ok());
  // The record as an older bench wrote it: no mean of per-frame PSNRs.
  const std::string path = bench.options.results_dir + "/fake-3-arc.json";
  auto older = ReadBenchRecord(path);
  ASSERT_TRUE(older.ok());
  for (BenchPoint& p : older->points) p.d1_psnr_mean_of_frames = std::nan("");
  ASSERT_TRUE(WriteBenchRecord(*older, path).ok());
  const std::size_t calls = bench.Calls().size();
  auto records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  int evals = 0;
  const std::vector<std::string> after = bench.Calls();
  for (std::size_t i = calls; i < after.size(); ++i) evals += after[i].rfind("eval ", 0) == 0;
  EXPECT_EQ(evals, 2 + 4 + 2);  // every point
  for (const BenchPoint& p : (*records)[0].points) {
    EXPECT_TRUE(HasMeanOfFramesPsnr(p)) << p.codec << p.quality;
  }
  EXPECT_EQ((*records)[0].bd_rates[0].psnr, kPsnrMeanOfFrames);
  bool logged = false;
  for (const std::string& line : bench.log)
    logged |= line.find("8 points were recorded without the mean of per-frame PSNRs") !=
              std::string::npos;
  EXPECT_TRUE(logged);
}

TEST(BenchRunnerTest, PointsRecordedBeforeColourAreMeasuredAgainWithIt) {
  FakeBench bench;
  bench.options.keep_work = true;  // so the baseline's summary could be reused
  ASSERT_TRUE(RunBench(bench.options, bench.events).ok());
  // The record and the baseline's summary as a bench before colour wrote them.
  const std::string path = bench.options.results_dir + "/fake-3-arc.json";
  auto older = ReadBenchRecord(path);
  ASSERT_TRUE(older.ok());
  for (BenchPoint& p : older->points) {
    p.colour_bytes_per_frame = p.y_psnr = p.yuv_psnr = std::nan("");
  }
  for (BenchEncode& e : older->encodes) e.colour_bytes_total = std::nan("");
  ASSERT_TRUE(WriteBenchRecord(*older, path).ok());
  const std::string summary_path = bench.options.work_dir + "/fake-3-arc/baseline/summary.json";
  nlohmann::json summary = nlohmann::json::parse(testing::ReadFile(summary_path));
  for (nlohmann::json& setting : summary.at("settings")) setting.erase("colour_bytes_total");
  testing::WriteFile(summary_path, summary.dump());

  const std::size_t calls = bench.Calls().size();
  auto records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  int baselines = 0, infos = 0, encodes = 0;
  const std::vector<std::string> after = bench.Calls();
  for (std::size_t i = calls; i < after.size(); ++i) {
    baselines += after[i].rfind("bench-baseline ", 0) == 0;
    infos += after[i].rfind("info ", 0) == 0;
    encodes += after[i].rfind("encode ", 0) == 0;
  }
  EXPECT_EQ(baselines, 1);  // the summary without colour bytes is not reused
  EXPECT_EQ(infos, 3);      // the kept files (AV1 q40 and q80, FFV1) are described again...
  EXPECT_EQ(encodes, 1);    // ...not encoded again (q66 fails every time)
  for (const BenchPoint& p : (*records)[0].points) {
    EXPECT_FALSE(std::isnan(p.colour_bytes_per_frame)) << p.codec << p.quality << p.level;
    EXPECT_DOUBLE_EQ(p.y_psnr, 33.5) << p.codec << p.quality << p.level;
  }
}

TEST(BenchRunnerTest, AFileEncodedAgainIsEvaluatedAgain) {
  FakeBench bench;
  ASSERT_TRUE(RunBench(bench.options, bench.events).ok());
  // The q40 file is gone (deleted to measure a new encoder): encoded, decoded and evaluated
  // again at every level, not kept from the record.
  const std::string file = bench.options.work_dir + "/fake-3-arc/av1-q40.mvid";
  ASSERT_TRUE(std::filesystem::remove(file));
  const std::size_t calls = bench.Calls().size();
  auto records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  const std::vector<std::string> after = bench.Calls();
  int encodes = 0, evals = 0;
  for (std::size_t i = calls; i < after.size(); ++i) {
    const bool q40 = after[i].find("av1-q40") != std::string::npos;
    encodes += q40 && after[i].rfind("encode ", 0) == 0;
    evals += q40 && after[i].rfind("eval ", 0) == 0;
  }
  EXPECT_EQ(encodes, 1);
  EXPECT_EQ(evals, 2);  // levels 0 and 1
  EXPECT_EQ((*records)[0].points.size(), 2u + 4u + 2u);
}

TEST(BenchRunnerTest, DrawsTheDefaultPointsWorstFrame) {
  FakeBench bench;
  bench.options.draw_stills = true;
  auto records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  const std::vector<std::string> calls = bench.Calls();
  const std::string& last = calls.back();
  EXPECT_EQ(last.rfind("render ", 0), 0u) << last;
  // The capture, the default encode (av1 quality 40) at its level and the ground truth, the
  // worst frame only, coloured by distance to the ground truth.
  EXPECT_NE(last.find("capture/manifest.json --compare "), std::string::npos) << last;
  EXPECT_NE(last.find("av1-q40.mvid --compare "), std::string::npos) << last;
  const int worst = (*records)[0].divergence.worst_frame;
  EXPECT_NE(last.find("--frames " + std::to_string(std::max(worst, 0)) + ":"), std::string::npos)
      << last;
  EXPECT_NE(last.find("--error-against "), std::string::npos) << last;
  EXPECT_NE(last.find("fake-3-arc-still.png"), std::string::npos) << last;
}

TEST(BenchRunnerTest, PointsWithoutPerFrameFiguresAreFilledFromTheirEvalJsonOrMeasuredAgain) {
  FakeBench bench;
  ASSERT_TRUE(RunBench(bench.options, bench.events).ok());
  // The record as the bench wrote it before it recorded per-frame figures.
  const std::string path = bench.options.results_dir + "/fake-3-arc.json";
  auto strip = [&path] {
    auto record = ReadBenchRecord(path);
    ASSERT_TRUE(record.ok());
    for (BenchPoint& p : record->points) p.frame_accuracy_rms = p.frame_d1_psnr = {};
    record->divergence = DivergenceCheck();
    ASSERT_TRUE(WriteBenchRecord(*record, path).ok());
  };
  auto has_all = [](const BenchRecord& r) {
    for (const BenchPoint& p : r.points) {
      if (!HasFrameFigures(p)) return false;
    }
    return true;
  };
  auto logged = [&bench](const std::string& text) {
    for (const std::string& line : bench.log) {
      if (line.find(text) != std::string::npos) return true;
    }
    return false;
  };
  strip();
  // Every eval JSON is still in the work folder: nothing is measured again (the one call is
  // the encode that always fails).
  std::size_t calls = bench.Calls().size();
  auto records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  std::vector<std::string> after = bench.Calls();
  ASSERT_EQ(after.size(), calls + 1);
  EXPECT_NE(after.back().find("--quality 66"), std::string::npos);
  EXPECT_TRUE(has_all((*records)[0]));
  EXPECT_EQ((*records)[0].divergence.frames_within, 1);
  EXPECT_TRUE(logged("8 points got their per-frame figures from their eval JSON")) << bench.log[0];

  // Two eval JSONs gone: those two points are measured again (the baseline's with its run,
  // its decoded frames being gone), the others filled.
  strip();
  const std::string work = bench.options.work_dir + "/fake-3-arc/";
  ASSERT_TRUE(std::filesystem::remove(work + "av1-q80-L1.eval.json"));
  ASSERT_TRUE(std::filesystem::remove(work + "draco-b10.eval.json"));
  calls = after.size();
  records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  after = bench.Calls();
  std::vector<std::string> new_calls(after.begin() + calls, after.end());
  int evals = 0, baselines = 0;
  for (const std::string& call : new_calls) {
    evals += call.rfind("eval ", 0) == 0;
    baselines += call.rfind("bench-baseline ", 0) == 0;
  }
  EXPECT_EQ(evals, 2);
  EXPECT_EQ(baselines, 1);
  EXPECT_EQ(new_calls.size(), 6u);  // + Draco decoding, decode, the failing encode
  EXPECT_TRUE(has_all((*records)[0]));
  EXPECT_TRUE(logged("6 points got their per-frame figures"));
  EXPECT_TRUE(
      logged("2 points were recorded without per-frame figures and their eval JSON is "
             "gone; measuring them again"));
  EXPECT_TRUE(logged("divergence of av1 q40 L1 against the baseline's 14 bits: 1/2 frames"));
}

TEST(BenchRunnerTest, StopsWhenProgressAsksAndKeepsWhatIsDone) {
  FakeBench bench;
  bench.events.progress = [](std::string_view, long done, long) { return done < 2; };
  auto records = RunBench(bench.options, bench.events);
  ASSERT_FALSE(records.ok());
  EXPECT_EQ(records.status().code(), StatusCode::kCancelled);
  auto saved = ReadBenchRecord(bench.options.results_dir + "/fake-3-arc.json");
  ASSERT_TRUE(saved.ok());
  EXPECT_TRUE(saved->simulate_ok);
  EXPECT_TRUE(saved->baseline_ok);
}

TEST(BenchRunnerTest, AMissingExecutableIsAClearError) {
  FakeBench bench;
  bench.options.meshvid = bench.dir.File("nothing-here");
  auto records = RunBench(bench.options, bench.events);
  ASSERT_FALSE(records.ok());
  EXPECT_NE(records.status().message().find("nothing-here"), std::string::npos);
}

TEST(BenchRunnerTest, SequencesRigsAndListsAreParsed) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir.File("sequences"));
  testing::WriteFile(dir.File("sequences/samba.obj"), "");
  testing::WriteFile(dir.File("sequences/samba.pc2"), "");
  testing::WriteFile(dir.File("sequences/lonely.obj"), "");  // no .pc2: not a sequence
  auto all = ResolveBenchSequences("", dir.path());
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 3u);
  EXPECT_EQ((*all)[0].name, "samba");
  EXPECT_EQ((*all)[0].ground_truth, dir.File("sequences/samba.obj"));
  EXPECT_DOUBLE_EQ((*all)[0].azimuth_deg, 90);
  EXPECT_EQ((*all)[1].ground_truth, "scene:arm-block");
  EXPECT_EQ((*all)[2].ground_truth, "scene:cloth");
  auto some = ResolveBenchSequences("scene:cloth,samba,/data/my dance.obj", dir.path());
  ASSERT_TRUE(some.ok()) << some.status().ToString();
  ASSERT_EQ(some->size(), 3u);
  EXPECT_EQ((*some)[0].name, "cloth");
  EXPECT_EQ((*some)[2].name, "my_dance");
  EXPECT_EQ((*some)[2].ground_truth, "/data/my dance.obj");
  auto unknown = ResolveBenchSequences("lonely", dir.path());
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.status().message().find("samba, arm-block, cloth"), std::string::npos)
      << unknown.status().message();

  auto rigs = ParseRigList("3-arc,8-ring");
  ASSERT_TRUE(rigs.ok());
  ASSERT_EQ(rigs->size(), 2u);
  EXPECT_EQ((*rigs)[1].name(), "8-ring");
  EXPECT_FALSE(ParseRigList("3-circle").ok());
  EXPECT_FALSE(ParseRigList("arc").ok());
  EXPECT_FALSE(ParseRigList("0-arc").ok());
  auto list = ParseIntList("8,10,12", 1, 30, "--bits");
  ASSERT_TRUE(list.ok());
  EXPECT_EQ(*list, (std::vector<int>{8, 10, 12}));
  auto bad = ParseIntList("8,,12", 1, 30, "--bits");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("--bits '8,,12'"), std::string::npos);
  EXPECT_FALSE(ParseIntList("31", 1, 30, "--bits").ok());

  auto extra = ParseEncodeArgs("  --rebase-gain 4\t--tune node_spacing=0.05 ");
  ASSERT_TRUE(extra.ok()) << extra.status().ToString();
  EXPECT_EQ(*extra,
            (std::vector<std::string>{"--rebase-gain", "4", "--tune", "node_spacing=0.05"}));
  ASSERT_TRUE(ParseEncodeArgs("").ok());
  EXPECT_TRUE(ParseEncodeArgs("")->empty());
  for (const char* reserved : {"-o x.mvid", "--quality 20", "--quality=20", "--frames 0:5", "-q"}) {
    auto refused = ParseEncodeArgs(reserved);
    ASSERT_FALSE(refused.ok()) << reserved;
    EXPECT_NE(refused.status().message().find("is set by the bench itself"), std::string::npos)
        << refused.status().message();
  }
}

TEST(BenchRunnerTest, ExtraEncodeArgumentsReachEveryEncodeAndAreKeptApart) {
  FakeBench bench;
  bench.options.qualities = {40};
  bench.options.encode_args = {"--rebase-gain", "4"};
  auto records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok()) << records.status().ToString();
  int encodes = 0;
  for (const std::string& call : bench.Calls()) {
    if (call.rfind("encode ", 0) != 0) continue;
    ++encodes;
    EXPECT_NE(call.find(" --rebase-gain 4 "), std::string::npos) << call;
  }
  EXPECT_EQ(encodes, 2);  // q40 and the lossless point
  EXPECT_EQ((*records)[0].encode_args, "--rebase-gain 4");
  for (const BenchEncode& e : (*records)[0].encodes) {
    if (e.method == kMethodMeshvid) {
      EXPECT_NE(e.command.find("--rebase-gain 4"), std::string::npos) << e.command;
    }
  }
  auto saved = ReadBenchRecord(bench.options.results_dir + "/fake-3-arc.json");
  ASSERT_TRUE(saved.ok()) << saved.status().ToString();
  EXPECT_EQ(saved->encode_args, "--rebase-gain 4");
  const std::string report = GenerateResultsMarkdown({*saved}, ReportOptions{});
  EXPECT_NE(report.find("was given `--rebase-gain 4`"), std::string::npos);

  // The defaults again: the record made with the extra arguments is not reused.
  const std::size_t calls = bench.Calls().size();
  bench.options.encode_args.clear();
  records = RunBench(bench.options, bench.events);
  ASSERT_TRUE(records.ok());
  bool afresh = false;
  for (const std::string& line : bench.log) {
    afresh |= line.find("made with other settings") != std::string::npos;
  }
  EXPECT_TRUE(afresh);
  const std::vector<std::string> after = bench.Calls();
  ASSERT_GT(after.size(), calls);
  for (std::size_t i = calls; i < after.size(); ++i) {
    EXPECT_EQ(after[i].find("--rebase-gain"), std::string::npos) << after[i];
  }
  EXPECT_EQ((*records)[0].encode_args, "");
}

TEST(ChildProcessTest, ExitCodesSignalsLogsAndCost) {
  testing::TempDir dir;
  auto run = RunChild({"/bin/sh", "-c", "echo first; echo second >&2; exit 3"}, dir.File("a.log"));
  ASSERT_TRUE(run.ok()) << run.status().ToString();
  EXPECT_EQ(run->exit_code, 3);
  EXPECT_FALSE(run->ok());
  EXPECT_GT(run->peak_rss_mb, 0.0);
  EXPECT_GE(run->wall_seconds, 0.0);
  EXPECT_EQ(LogTail(dir.File("a.log")), "first; second");
  EXPECT_EQ(LogTail(dir.File("a.log"), 1), "second");
  run = RunChild({"/bin/sh", "-c", "kill -TERM $$"}, "");
  ASSERT_TRUE(run.ok());
  EXPECT_EQ(run->signal, 15);
  EXPECT_FALSE(run->ok());
  run = RunChild({"sh", "-c", "printf 'bar 1/3\\rbar 3/3  \\n'"}, dir.File("b.log"));
  ASSERT_TRUE(run.ok());
  EXPECT_TRUE(run->ok());
  EXPECT_EQ(LogTail(dir.File("b.log")), "bar 3/3");
  run = RunChild({dir.File("no-such-program")}, "");
  EXPECT_TRUE(!run.ok() || run->exit_code == 127);
  EXPECT_EQ(ShellQuoteCommand({"meshvid", "eval", "--test", "a b/f{frame:04}.ply", "it's"}),
            "meshvid eval --test 'a b/f{frame:04}.ply' 'it'\\''s'");
  EXPECT_EQ(FindProgram("sh").empty(), false);
  EXPECT_EQ(FindProgram("surely-not-a-program-xyz"), "");
}

}  // namespace
}  // namespace meshvid
