// A small fake set of bench records for the bench_* tests: a baseline of four Draco points
// and meshvid AV1 at exactly half the baseline's rate at every PSNR, plus one lossless point
// and a failed step; per-frame figures, and the eval JSON they come from.
#ifndef MESHVID_TESTS_BENCH_FAKE_RECORDS_H_
#define MESHVID_TESTS_BENCH_FAKE_RECORDS_H_

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/bench/bench_divergence.h"
#include "tools/bench/bench_record.h"
#include "tools/json/json_number.h"

namespace meshvid::testing {

/// The record "fake-3-arc": baseline bits 8..14 at 30..45 dB; AV1 q20..q80 at level 1
/// with half the rate at the same PSNRs (BD-rate -50%), at level 0 with a PSNR range that
/// does not overlap; FFV1 lossless at PSNR inf (100 dB as the mean of frames); one failed HEVC
/// encode. The PSNRs above are the means of frames; the PSNRs of the mean MSE are lower, by
/// 1 dB for the baseline and 4 dB for meshvid (as if it had a few bad frames), so a BD-rate on
/// them would differ.
///
/// Per-frame figures (10 frames) of every point but the lossless one: the baseline's accuracy
/// RMS is 0.002 on every frame; meshvid's 0.0022 (1.1x) but on frame 7, 0.0031 (1.55x); each
/// frame's D1 PSNR is the point's mean of frames. So the divergence check (default point AV1
/// q40 at level 1, its finest; baseline best: 14 bits, 45 dB) finds 9 of 10 frames within
/// 1.25x (missed), frame 7 the worst, and 35 against 45 dB (missed).
inline BenchRecord FakeRecord() {
  BenchRecord r;
  r.sequence = "fake";
  r.ground_truth = "scene:fake";
  r.rig = "3-arc";
  r.views = 3;
  r.layout = "arc";
  r.frames = 10;
  r.frame_rate = 25;
  r.eval_samples = 50000;
  r.capture = "work/fake-3-arc/capture/manifest.json";
  r.reference = "work/fake-3-arc/capture/ground_truth.obj";
  r.date = "2026-11-22T10:00:00Z";
  r.run_key = "gt=scene:fake;frames=10";
  r.machine = {"Test CPU @ 2.7GHz", 2, 24.0, "Linux 6.1 x86_64"};
  r.simulate_ok = true;
  r.simulate_command = "meshvid simulate scene:fake -o work/fake-3-arc/capture --views 3 -q";
  r.simulate_cost = {1.5, 2.5, 95};
  r.baseline_ok = true;
  r.baseline_command = "meshvid bench-baseline work/fake-3-arc/capture/manifest.json -o b -q";
  r.baseline_cost = {30, 31, 250};
  r.baseline_fuse_seconds = 25;
  r.bench_process_peak_mb = 21;
  const double psnrs[] = {30, 35, 40, 45};
  for (int i = 0; i < 4; ++i) {
    BenchPoint p;
    p.method = kMethodBaseline;
    p.codec = "draco";
    p.quality = 8 + 2 * i;
    p.ok = true;
    p.frames = 10;
    p.bytes_per_frame = 100000.0 * (1 << i);
    p.mbit_per_s = p.bytes_per_frame * 8 * 25 / 1e6;
    p.d1_psnr_mean_of_frames = psnrs[i];
    p.d1_psnr = psnrs[i] - 1;
    p.d2_psnr_mean_of_frames = psnrs[i] + 4;
    p.d2_psnr = psnrs[i] + 3;
    p.accuracy_rms = 0.002;
    p.completeness_rms = 0.004;
    p.coverage = 0.9;
    p.decode_fps = 30;
    p.encode_fps = 0.4;
    p.encode_peak_mb = p.decode_peak_mb = 250;
    p.commands = {r.baseline_command};
    p.frame_accuracy_rms.assign(10, 0.002);
    p.frame_d1_psnr.assign(10, psnrs[i]);
    r.points.push_back(p);

    BenchPoint m = p;
    m.method = kMethodMeshvid;
    m.codec = "av1";
    m.quality = 20 + 20 * i;
    m.level = 1;
    m.d1_psnr = psnrs[i] - 4;
    m.bytes_per_frame = p.bytes_per_frame / 2;
    m.mbit_per_s = p.mbit_per_s / 2;
    m.coverage = 0.95;
    m.decode_fps = 600;
    m.encode_fps = 5;
    m.encode_peak_mb = 400;
    m.decode_peak_mb = 60;
    m.frame_accuracy_rms.assign(10, 0.0022);
    m.frame_accuracy_rms[7] = 0.0031;
    m.commands = {
        "meshvid encode c -o av1-q" + std::to_string(m.quality) + ".mvid -q",
        "meshvid decode av1-q" + std::to_string(m.quality) + ".mvid --level 1 --no-write -q"};
    r.points.push_back(m);
    m.level = 0;
    m.d1_psnr_mean_of_frames = 20 + i;  // below every baseline point: no overlap
    m.frame_d1_psnr.assign(10, 20 + i);
    m.d1_psnr = 16 + i;
    m.decode_fps = 2000;
    r.points.push_back(m);
  }
  BenchPoint lossless;
  lossless.method = kMethodMeshvid;
  lossless.codec = "ffv1";
  lossless.quality = 100;
  lossless.level = 1;
  lossless.ok = true;
  lossless.bytes_per_frame = 900000;
  lossless.mbit_per_s = 180;
  lossless.d1_psnr = std::numeric_limits<double>::infinity();
  lossless.d1_psnr_mean_of_frames = 100;  // every frame exact: each capped at 100 dB
  lossless.d2_psnr = 70;
  lossless.d2_psnr_mean_of_frames = 71;
  lossless.coverage = 0.96;
  r.points.push_back(lossless);
  BenchEncode failed;
  failed.method = kMethodMeshvid;
  failed.codec = "hevc";
  failed.quality = 40;
  failed.error = "encode: exit code 1: out of cheese";
  failed.command = "meshvid encode c -o hevc-q40.mvid --codec hevc -q";
  r.encodes.push_back(failed);
  ComputeBdRates(r);
  ComputeDivergence(r);
  return r;
}

/// FakeRecord's JSON as meshvid bench wrote it before it recorded per-frame figures (but with
/// the mean of per-frame PSNRs): no "frame_accuracy_rms"/"frame_d1_psnr" in the points, no
/// "divergence".
inline std::string RecordJsonWithoutFrameFigures() {
  nlohmann::json j = nlohmann::json::parse(BenchRecordToJson(FakeRecord()));
  for (nlohmann::json& p : j["points"]) {
    p.erase("frame_accuracy_rms");
    p.erase("frame_d1_psnr");
  }
  j.erase("divergence");
  return j.dump(2) + "\n";
}

/// The `meshvid eval --json` text (tools/eval/eval_report.cc) a point's figures come from:
/// its means, and its per-frame accuracy RMS and D1 PSNR (other per-frame figures made up).
inline std::string FakeEvalJson(const BenchPoint& p) {
  const auto number = [](double v) { return JsonNumber(v); };  // as the eval writes them
  nlohmann::json j;
  j["settings"] = {{"ref", "gt.obj"}, {"test", "test"}, {"samples", 50000}};
  j["peak"] = 1.7;
  j["frames"] = nlohmann::json::array();
  for (std::size_t t = 0; t < p.frame_accuracy_rms.size(); ++t) {
    j["frames"].push_back({{"frame", t},
                           {"d1_psnr", number(p.frame_d1_psnr[t])},
                           {"d2_psnr", number(p.frame_d1_psnr[t] + 4)},
                           {"accuracy_rms", number(p.frame_accuracy_rms[t])},
                           {"completeness_rms", 0.004},
                           {"hausdorff", 0.01},
                           {"coverage", 0.9}});
  }
  j["mean"] = {{"d1_psnr", number(p.d1_psnr)},
               {"d2_psnr", number(p.d2_psnr)},
               {"accuracy_rms", number(p.accuracy_rms)},
               {"completeness_rms", number(p.completeness_rms)},
               {"hausdorff", number(p.hausdorff)},
               {"coverage", number(p.coverage)},
               {"d1_psnr_mean_of_frames", number(p.d1_psnr_mean_of_frames)},
               {"d2_psnr_mean_of_frames", number(p.d2_psnr_mean_of_frames)}};
  return j.dump(2) + "\n";
}

/// FakeRecord's JSON as meshvid bench wrote it before it recorded the mean of per-frame PSNRs:
/// no "d1_psnr_mean_of_frames"/"d2_psnr_mean_of_frames" in the points, no "psnr" in the
/// BD-rates (then computed on the PSNR of the mean MSE), no per-frame figures, no
/// "divergence".
inline std::string OlderFakeRecordJson() {
  BenchRecord r = FakeRecord();
  for (BenchPoint& p : r.points) {
    p.d1_psnr_mean_of_frames = p.d2_psnr_mean_of_frames = std::nan("");
  }
  ComputeBdRates(r);  // on the PSNR of the mean MSE, as the older bench did
  nlohmann::json j = nlohmann::json::parse(BenchRecordToJson(r));
  for (nlohmann::json& p : j["points"]) {
    p.erase("d1_psnr_mean_of_frames");
    p.erase("d2_psnr_mean_of_frames");
    p.erase("frame_accuracy_rms");
    p.erase("frame_d1_psnr");
  }
  for (nlohmann::json& b : j["bd_rates"]) b.erase("psnr");
  j.erase("divergence");
  return j.dump(2) + "\n";
}

}  // namespace meshvid::testing

#endif  // MESHVID_TESTS_BENCH_FAKE_RECORDS_H_
