// Displacement packings compared by bits at equal error: the analytic sequence of the codec
// tests (66-vertex base, L = 3, 12 frames, groups of 6) coded with HEVC at several QPs in each
// packing; counters give the video bytes and the RMS reconstruction error in 10-bit steps.
#include <benchmark/benchmark.h>

#include "codec/dec/mvid_decoder.h"
#include "tests/analytic_mvid.h"

namespace meshvid {
namespace {

constexpr int kFrames = 12;
constexpr float kStep = 0.04f / 1023;  // the detail spans [-0.02, 0.02]

void BM_Packing(benchmark::State& state) {
  const auto packing = static_cast<DisplacementPacking>(state.range(0));
  const TriangleMesh base = testing::SphereMesh(2);
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kHevc;
  settings.levels = 3;
  settings.gof_size = 6;
  settings.qp = static_cast<int>(state.range(1));
  settings.packing = packing;
  MvidWriteStats stats;
  testing::ReconstructionError error;
  for (auto _ : state) {
    auto bytes = testing::WriteAnalyticMvid(base, testing::TwoSegments(base), kFrames, settings,
                                            &stats);
    if (!bytes.ok()) return state.SkipWithError(bytes.status().ToString().c_str());
    auto decoder = MvidDecoder::OpenMemory(std::move(*bytes));
    if (!decoder.ok()) return state.SkipWithError(decoder.status().ToString().c_str());
    auto measured = testing::MeasureReconstructionError(**decoder, 3, kFrames);
    if (!measured.ok()) return state.SkipWithError(measured.status().ToString().c_str());
    error = *measured;
  }
  state.counters["video_bytes"] = static_cast<double>(stats.video_bytes);
  state.counters["rms_steps"] = error.rms / kStep;
  state.counters["max_steps"] = error.max / kStep;
  state.SetLabel(packing == DisplacementPacking::kLatticeOrder ? "lattice order"
                                                               : "triangle blocks");
}

BENCHMARK(BM_Packing)
    ->ArgsProduct({{static_cast<int>(DisplacementPacking::kTriangleBlocks),
                    static_cast<int>(DisplacementPacking::kLatticeOrder)},
                   {4, 8, 16, 24, 32}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshvid

BENCHMARK_MAIN();
