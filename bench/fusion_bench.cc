// Speed of the view fusion (FuseRangeMeshes) on samba seen by 3 range cameras of 640x480 on
// the default arc (turned to face the dancer), the fusion of the encoder's base meshes and of
// meshvid bench's baseline, and of the decimation that makes a base of the fused surface.
// Frames are simulated once, before timing.
//   build/bench/fusion_bench [--benchmark_filter=...]
// Needs the shared data (MESHVID_SHARED_DATA or ../shared/data); skips otherwise.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/samba_frames.h"
#include "codec/enc/encoder.h"
#include "codec/enc/fusion/decimation.h"
#include "codec/enc/fusion/surface_fusion.h"
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
  float size = 0;  ///< the ground truth's bounding-box diagonal over the frames

  SambaViews() {
    SambaGroundTruth truth = LoadSambaGroundTruth(kFrames);
    if (!truth.error.empty()) {
      error = std::move(truth.error);
      return;
    }
    size = truth.bounds.diagonal().norm();
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

/// The views, simulated on first use and shared by the benchmarks.
const SambaViews* Samba() {
  static const SambaViews* samba = new SambaViews;
  return samba;
}

/// One frame's 3 views fused into one surface, at the default settings.
void BM_SambaFuseThreeViews(benchmark::State& state) {
  const SambaViews* samba = Samba();
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

/// A key frame's base: one frame's 3 views fused from tuning.base_fusion_points points, as the
/// encoder fuses a base, decimated with the encoder's default base bounds (base_vertices, 1%
/// of the size from every fused vertex, the normal deviation, edges of at most 3% of the size
/// as the encoder does). Fused once per frame before timing; every iteration
/// decimates each of the frames once.
void BM_SambaDecimateBase(benchmark::State& state) {
  const SambaViews* samba = Samba();
  if (!samba->error.empty()) {
    state.SkipWithError(samba->error.c_str());
    return;
  }
  const EncoderOptions defaults;
  static const std::vector<TriangleMesh>* fused = [samba, &defaults] {
    auto* meshes = new std::vector<TriangleMesh>;
    SurfaceFusionOptions options;
    options.max_points = defaults.tuning.base_fusion_points;
    for (const auto& views : samba->frames) {
      auto mesh = FuseRangeMeshes(views, options);
      if (mesh.ok()) meshes->push_back(std::move(*mesh));
    }
    return meshes;
  }();
  if (fused->size() != samba->frames.size()) {
    state.SkipWithError("a frame failed to fuse");
    return;
  }
  DecimationOptions options;
  options.target_vertices = defaults.base_vertices;
  // The fractions of the size the encoder derives the two lengths from.
  options.max_error = 0.01 * samba->size;
  options.max_normal_deviation_degrees = defaults.tuning.base_max_normal_deviation_degrees;
  options.max_edge_length = 0.03 * samba->size;
  long long input = 0, output = 0;
  const double cpu_start = ProcessCpuSeconds();
  for (auto _ : state) {
    for (const TriangleMesh& mesh : *fused) {  // every frame once per iteration
      auto base = DecimateMesh(mesh, options);
      if (!base.ok()) {
        state.SkipWithError(base.status().ToString().c_str());
        return;
      }
      input += static_cast<long long>(mesh.vertex_count());
      output += static_cast<long long>(base->vertex_count());
    }
  }
  const double bases = static_cast<double>(state.iterations() * fused->size());
  state.counters["bases/s"] = benchmark::Counter(bases, benchmark::Counter::kIsRate);
  state.counters["cpu_ms/base"] = 1000.0 * (ProcessCpuSeconds() - cpu_start) / bases;
  state.counters["input_vertices"] = static_cast<double>(input) / bases;
  state.counters["base_vertices"] = static_cast<double>(output) / bases;
}

BENCHMARK(BM_SambaDecimateBase)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace meshvid

BENCHMARK_MAIN();
