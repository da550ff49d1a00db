// Speed of the view fusion (FuseRangeMeshes) on samba seen by 3 range cameras of 640x480 on
// the default arc (turned to face the dancer), the fusion of the encoder's base meshes and of
// meshvid bench's baseline. Frames are simulated once, before timing.
//   build/bench/fusion_bench [--benchmark_filter=...]
// Needs the shared data (MESHVID_SHARED_DATA or ../shared/data); skips otherwise.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/samba_frames.h"
#include "codec/enc/surface_fusion.h"
#include "tools/io/mesh_sequence.h"
#include "tools/sim/range_sensor.h"
#include "tools/sim/rig.h"
#include "tools/sim/simulator.h"

namespace meshvid {
namespace {

constexpr int kFrames = 10;  // samba frames simulated for the loop

/// Process CPU time (all threads), meaningful when other jobs share the machine.
double ProcessCpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

/// The range meshes of samba's first frames from a 3-view arc, made once.
struct SambaViews {
  std::string error;
  std::vector<std::vector<TriangleMesh>> frames;

  SambaViews() {
    SambaGroundTruth truth = LoadSambaGroundTruth(kFrames);
    if (!truth.error.empty()) {
      error = std::move(truth.error);
      return;
    }
    const Eigen::AlignedBox3d box(truth.bounds.min().cast<double>(),
                                  truth.bounds.max().cast<double>());
    RigOptions rig;
    rig.azimuth_deg = 90;  // samba's dancer faces +x
    auto cameras = PlaceCameras(box, rig);
    if (!cameras.ok()) {
      error = cameras.status().ToString();
      return;
    }
    auto simulator = CaptureSimulator::Create(*cameras, SensorOptions());
    if (!simulator.ok()) {
      error = simulator.status().ToString();
      return;
    }
    for (int t = 0; t < kFrames; ++t) {
      auto views = (*simulator)->SimulateFrame(truth.frames[t], t);
      if (!views.ok()) {
        error = views.status().ToString();
        return;
      }
      frames.push_back(std::move(*views));
    }
  }
};

/// One frame's 3 views fused into one surface, at the default settings.
void BM_SambaFuseThreeViews(benchmark::State& state) {
  static const SambaViews* samba = new SambaViews;
  if (!samba->error.empty()) {
    state.SkipWithError(samba->error.c_str());
    return;
  }
  long long vertices = 0;
  int t = 0;
  const double cpu_start = ProcessCpuSeconds();
  for (auto _ : state) {
    auto fused = FuseRangeMeshes(samba->frames[t % kFrames]);
    if (!fused.ok()) {
      state.SkipWithError(fused.status().ToString().c_str());
      return;
    }
    vertices += static_cast<long long>(fused->vertex_count());
    ++t;
  }
  const double iterations = static_cast<double>(state.iterations());
  state.counters["frames/s"] = benchmark::Counter(iterations, benchmark::Counter::kIsRate);
  state.counters["cpu_ms/frame"] = 1000.0 * (ProcessCpuSeconds() - cpu_start) / iterations;
  state.counters["vertices"] = static_cast<double>(vertices) / iterations;
}

BENCHMARK(BM_SambaFuseThreeViews)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace meshvid

BENCHMARK_MAIN();
