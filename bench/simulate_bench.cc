// Speed of the capture simulator on samba (3 views of 640x480 by default): ray casting +
// sensor model, + meshing (the simulator core), and PLY writing, reported separately.
//   build-NAME/bench/simulate_bench [--benchmark_filter=...]
// Needs the shared data (MESHVID_SHARED_DATA or ../shared/data); skips otherwise.
#include <benchmark/benchmark.h>

#include <ctime>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bench/samba_frames.h"
#include "tools/io/mesh_io.h"
#include "tools/io/mesh_sequence.h"
#include "tools/sim/range_sensor.h"
#include "tools/sim/rig.h"
#include "tools/sim/simulator.h"

namespace meshvid {
namespace {

constexpr int kFrames = 25;  // samba frames kept in memory for the loop

/// Process CPU time (all threads), meaningful when other jobs share the machine.
double ProcessCpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

void SetCpuCounter(benchmark::State& state, double cpu_start) {
  state.counters["cpu_ms/frame"] =
      1000.0 * (ProcessCpuSeconds() - cpu_start) / static_cast<double>(state.iterations());
}

/// Samba's first frames and a default rig around them, loaded once.
struct SambaFixture {
  std::string error;
  std::vector<TriangleMesh> frames;
  std::vector<ViewCalibration> views;

  SambaFixture() {
    SambaGroundTruth truth = LoadSambaGroundTruth(kFrames);
    if (!truth.error.empty()) {
      error = std::move(truth.error);
      return;
    }
    frames = std::move(truth.frames);
    const Eigen::AlignedBox3d box(truth.bounds.min().cast<double>(),
                                  truth.bounds.max().cast<double>());
    auto placed = PlaceCameras(box, RigOptions());
    if (!placed.ok()) error = placed.status().ToString();
    else views = *placed;
  }
};

const SambaFixture& Samba() {
  static const SambaFixture* fixture = new SambaFixture;
  return *fixture;
}

std::unique_ptr<CaptureSimulator> MakeSimulator(benchmark::State& state) {
  const SambaFixture& samba = Samba();
  if (!samba.error.empty()) {
    state.SkipWithError(samba.error.c_str());
    return nullptr;
  }
  auto simulator = CaptureSimulator::Create(samba.views, SensorOptions());
  if (!simulator.ok()) {
    state.SkipWithError(simulator.status().ToString().c_str());
    return nullptr;
  }
  return std::move(*simulator);
}

/// Ray casting (BVH build included) + noise, grazing, drop-out: range images only.
void BM_SambaScan(benchmark::State& state) {
  auto simulator = MakeSimulator(state);
  if (simulator == nullptr) return;
  int t = 0;
  const double cpu_start = ProcessCpuSeconds();
  for (auto _ : state) {
    auto scans = simulator->ScanFrame(Samba().frames[t % kFrames], t);
    benchmark::DoNotOptimize(scans);
    ++t;
  }
  state.counters["frames/s"] = benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
  SetCpuCounter(state, cpu_start);
}

/// The simulator core: ScanFrame + TriangulateRangeGrid for every view.
void BM_SambaScanAndMesh(benchmark::State& state) {
  auto simulator = MakeSimulator(state);
  if (simulator == nullptr) return;
  int t = 0;
  long long triangles = 0;
  const double cpu_start = ProcessCpuSeconds();
  for (auto _ : state) {
    auto meshes = simulator->SimulateFrame(Samba().frames[t % kFrames], t);
    if (!meshes.ok()) {
      state.SkipWithError(meshes.status().ToString().c_str());
      return;
    }
    for (const TriangleMesh& mesh : *meshes) triangles += mesh.triangle_count();
    ++t;
  }
  state.counters["frames/s"] = benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
  SetCpuCounter(state, cpu_start);
  state.counters["triangles/view"] = static_cast<double>(triangles) / (3.0 * state.iterations());
}

/// Writing one frame's 3 view meshes as binary PLY (to the system temp folder).
void BM_SambaWritePly(benchmark::State& state) {
  auto simulator = MakeSimulator(state);
  if (simulator == nullptr) return;
  auto meshes = simulator->SimulateFrame(Samba().frames[0], 0);
  if (!meshes.ok()) {
    state.SkipWithError(meshes.status().ToString().c_str());
    return;
  }
  const std::string dir =
      (std::filesystem::temp_directory_path() / "meshvid_simulate_bench").string();
  std::filesystem::create_directories(dir);
  long long bytes = 0;
  const double cpu_start = ProcessCpuSeconds();
  for (auto _ : state) {
    for (std::size_t v = 0; v < meshes->size(); ++v) {
      const std::string path = dir + "/" + SimulatedViewFileName(0, static_cast<int>(v));
      if (Status status = WriteMesh(path, (*meshes)[v]); !status.ok()) {
        state.SkipWithError(status.ToString().c_str());
        return;
      }
      bytes += static_cast<long long>(std::filesystem::file_size(path));
    }
  }
  std::filesystem::remove_all(dir);
  state.counters["frames/s"] = benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
  SetCpuCounter(state, cpu_start);
  state.SetBytesProcessed(bytes);
}

BENCHMARK(BM_SambaScan)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SambaScanAndMesh)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SambaWritePly)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace meshvid

BENCHMARK_MAIN();
