// Decoder speed: frames per second of MvidDecoder on one core (video decode, posing,
// subdivision and displacement included; no disk I/O), on an analytic sequence whose base
// mesh has 2,452 vertices, so level 2 gives 39,202 vertices per frame.
#include <benchmark/benchmark.h>

#include <map>
#include <utility>

#include "codec/dec/mvid_decoder.h"
#include "tests/analytic_mvid.h"

namespace meshvid {
namespace {

constexpr int kFrames = 64;

/// The bytes of the analytic sequence coded with `codec` at `levels`, made once per setting.
const std::vector<std::uint8_t>& File(VideoCodec codec, int levels) {
  static std::map<std::pair<int, int>, std::vector<std::uint8_t>> files;
  auto& bytes = files[{static_cast<int>(codec), levels}];
  if (bytes.empty()) {
    const TriangleMesh base = testing::LatLongSphere(49, 50);  // 2,452 vertices
    MvidWriterSettings settings;
    settings.codec = codec;
    settings.levels = levels;
    settings.qp = codec == VideoCodec::kAv1 ? 24 : 20;
    settings.gof_size = 32;
    auto written =
        testing::WriteAnalyticMvid(base, testing::TwoSegments(base), kFrames, settings);
    if (written.ok()) bytes = std::move(*written);
  }
  return bytes;
}

/// Decodes every frame at `level` in order, as a player does; one iteration = one sequence.
void BM_DecodeSequence(benchmark::State& state) {
  const auto codec = static_cast<VideoCodec>(state.range(0));
  const int levels = static_cast<int>(state.range(1));
  const int level = static_cast<int>(state.range(2));
  const std::vector<std::uint8_t>& bytes = File(codec, levels);
  if (bytes.empty()) {
    state.SkipWithError("cannot write the benchmark file");
    return;
  }
  std::vector<Eigen::Vector3f> positions;
  std::size_t vertices = 0;
  for (auto _ : state) {
    auto decoder = MvidDecoder::OpenMemory(bytes, MvidDecoderOptions{.threads = 1});
    if (!decoder.ok()) {
      state.SkipWithError(decoder.status().ToString().c_str());
      return;
    }
    for (std::uint32_t f = 0; f < kFrames; ++f) {
      if (!(*decoder)->DecodePositions(f, level, &positions).ok()) {
        state.SkipWithError("decode failed");
        return;
      }
    }
    vertices = positions.size();
    benchmark::DoNotOptimize(positions.data());
  }
  state.counters["frames/s"] =
      benchmark::Counter(double(kFrames) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["bytes/frame"] = static_cast<double>(bytes.size()) / kFrames;
  state.SetLabel(std::string(VideoCodecName(codec)) + " L=" + std::to_string(levels) +
                 " level " + std::to_string(level));
}

BENCHMARK(BM_DecodeSequence)
    ->Args({static_cast<int>(VideoCodec::kHevc), 2, 2})
    ->Args({static_cast<int>(VideoCodec::kHevc), 3, 2})
    ->Args({static_cast<int>(VideoCodec::kHevc), 3, 3})
    ->Args({static_cast<int>(VideoCodec::kAv1), 2, 2})
    ->Args({static_cast<int>(VideoCodec::kFfv1), 2, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace meshvid

BENCHMARK_MAIN();
