// Decoder speed: frames per second of MvidDecoder on one core (video decode, posing,
// subdivision and displacement included; no disk I/O), on an analytic sequence whose base
// mesh has 2,452 vertices, so level 2 gives 39,202 vertices per frame; with a colour stream,
// each frame's colours are decoded too.
#include <benchmark/benchmark.h>

#include <map>
#include <tuple>
#include <utility>

#include "codec/dec/mvid_decoder.h"
#include "tests/analytic_mvid.h"

namespace meshvid {
namespace {

constexpr int kFrames = 64;

/// The bytes of the analytic sequence coded with `codec` at `levels`, with a colour stream or
/// not, made once per setting.
const std::vector<std::uint8_t>& File(VideoCodec codec, int levels, bool colour) {
  static std::map<std::tuple<int, int, bool>, std::vector<std::uint8_t>> files;
  auto& bytes = files[{static_cast<int>(codec), levels, colour}];
  if (bytes.empty()) {
    const TriangleMesh base = testing::LatLongSphere(49, 50);  // 2,452 vertices
    MvidWriterSettings settings;
    settings.codec = codec;
    settings.levels = levels;
    settings.qp = codec == VideoCodec::kAv1 ? 24 : 20;
    settings.gof_size = 32;
    settings.colour = colour;
    settings.colour_qp = settings.qp;
    auto written =
        testing::WriteAnalyticMvid(base, testing::TwoSegments(base), kFrames, settings);
    if (written.ok()) bytes = std::move(*written);
  }
  return bytes;
}

/// Decodes every frame at `level` in order, as a player does, with its colours if the file
/// has them; one iteration = one sequence.
void BM_DecodeSequence(benchmark::State& state) {
  const auto codec = static_cast<VideoCodec>(state.range(0));
  const int levels = static_cast<int>(state.range(1));
  const int level = static_cast<int>(state.range(2));
  const bool colour = state.range(3) != 0;
  const std::vector<std::uint8_t>& bytes = File(codec, levels, colour);
  if (bytes.empty()) {
    state.SkipWithError("cannot write the benchmark file");
    return;
  }
  std::vector<Eigen::Vector3f> positions;
  std::vector<Colour> colours;
  std::size_t vertices = 0;
  for (auto _ : state) {
    auto decoder = MvidDecoder::OpenMemory(bytes, MvidDecoderOptions{.threads = 1});
    if (!decoder.ok()) {
      state.SkipWithError(decoder.status().ToString().c_str());
      return;
    }
    for (std::uint32_t f = 0; f < kFrames; ++f) {
      if (!(*decoder)->DecodePositions(f, level, &positions).ok() ||
          (colour && !(*decoder)->DecodeColours(f, level, &colours).ok())) {
        state.SkipWithError("decode failed");
        return;
      }
    }
    vertices = positions.size();
    benchmark::DoNotOptimize(positions.data());
    benchmark::DoNotOptimize(colours.data());
  }
  state.counters["frames/s"] =
      benchmark::Counter(double(kFrames) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["bytes/frame"] = static_cast<double>(bytes.size()) / kFrames;
  state.SetLabel(std::string(VideoCodecName(codec)) + " L=" + std::to_string(levels) + " level " +
                 std::to_string(level) + (colour ? " colour" : ""));
}

BENCHMARK(BM_DecodeSequence)
    ->Args({static_cast<int>(VideoCodec::kHevc), 2, 2, 0})
    ->Args({static_cast<int>(VideoCodec::kHevc), 3, 2, 0})
    ->Args({static_cast<int>(VideoCodec::kHevc), 3, 3, 0})
    ->Args({static_cast<int>(VideoCodec::kAv1), 2, 2, 0})
    ->Args({static_cast<int>(VideoCodec::kFfv1), 2, 2, 0})
    ->Args({static_cast<int>(VideoCodec::kHevc), 2, 2, 1})
    ->Args({static_cast<int>(VideoCodec::kHevc), 3, 3, 1})
    ->Args({static_cast<int>(VideoCodec::kAv1), 2, 2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace meshvid

BENCHMARK_MAIN();
