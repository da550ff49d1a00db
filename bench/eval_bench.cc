// Speed of `meshvid eval`: samba ground truth against a perturbed copy of itself, 200k
// samples per surface (the default). Target: >= 5 frames/s on 2 cores.
// Needs the shared data (MESHVID_SHARED_DATA, or ../shared/data beside the checkout).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tools/eval/evaluation.h"
#include "tools/eval/metrics.h"
#include "tools/eval/sampling.h"
#include "tools/io/mesh_sequence.h"

namespace meshvid {
namespace {

constexpr int kFrames = 8;

std::string SambaPath() {
  const char* env = std::getenv("MESHVID_SHARED_DATA");
  const std::string dir = env != nullptr ? env : MESHVID_DEFAULT_SHARED_DATA;
  const std::string path = dir + "/sequences/samba.obj";
  return std::filesystem::exists(path) ? path : "";
}

/// Moves every vertex along its normal by a deterministic pseudo-random amount in
/// [-amplitude, amplitude]: a stand-in for a reconstruction with millimetre errors.
TriangleMesh Perturb(const TriangleMesh& mesh, float amplitude, std::uint64_t seed) {
  TriangleMesh out = mesh;
  const std::vector<Eigen::Vector3f> normals = ComputeVertexNormals(mesh);
  for (std::size_t i = 0; i < out.positions.size(); ++i) {
    const float r = static_cast<float>(2.0 * UniformHash(seed, i, 0) - 1.0);
    out.positions[i] += amplitude * r * normals[i];
  }
  return out;
}

/// CPU seconds used so far by every thread of the process: with other jobs on the machine,
/// wall time overstates the cost, and CPU time / cores gives the dedicated-machine time.
double ProcessCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
         1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

/// The first kFrames frames of samba and their perturbed copies, loaded once.
struct SambaFrames {
  std::vector<TriangleMesh> ref, test;
  double peak = 0;
};

const SambaFrames* LoadSamba() {
  static const std::unique_ptr<SambaFrames> frames = []() -> std::unique_ptr<SambaFrames> {
    const std::string path = SambaPath();
    if (path.empty()) return nullptr;
    auto sequence = OpenMeshSequence(path);
    if (!sequence.ok()) return nullptr;
    auto result = std::make_unique<SambaFrames>();
    auto peak = SequenceBoundingBoxDiagonal(**sequence);
    if (!peak.ok()) return nullptr;
    result->peak = *peak;
    for (int t = 0; t < kFrames; ++t) {
      auto mesh = (*sequence)->Frame(t);
      if (!mesh.ok()) return nullptr;
      result->test.push_back(Perturb(*mesh, 0.002f, t));  // +-2 mm
      result->ref.push_back(std::move(mesh).value());
    }
    return result;
  }();
  return frames.get();
}

/// One frame's metrics (sampling, k-d trees, BVHs, both directions); items = frames.
void BM_EvalFrameSamba(benchmark::State& state) {
  const SambaFrames* samba = LoadSamba();
  if (samba == nullptr) {
    state.SkipWithError("shared data absent: set MESHVID_SHARED_DATA to the data folder");
    return;
  }
  MetricOptions options;
  options.samples = static_cast<std::size_t>(state.range(0));
  options.peak = samba->peak;
  options.coverage_tolerance = kDefaultCoverageToleranceRatio * samba->peak;
  int t = 0;
  double d1_psnr = 0, accuracy = 0;
  const double cpu_start = ProcessCpuSeconds();
  for (auto _ : state) {
    auto metrics = ComputeFrameMetrics(samba->ref[t], samba->test[t], options);
    if (!metrics.ok()) {
      state.SkipWithError(metrics.status().ToString().c_str());
      return;
    }
    d1_psnr = metrics->d1_psnr;
    accuracy = metrics->accuracy_rms;
    t = (t + 1) % kFrames;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["cpu_s_per_frame"] =
      (ProcessCpuSeconds() - cpu_start) / static_cast<double>(state.iterations());
  state.counters["d1_psnr_db"] = d1_psnr;
  state.counters["accuracy_mm"] = 1000.0 * accuracy;
}
BENCHMARK(BM_EvalFrameSamba)->Arg(200000)->Arg(50000)->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// Sampling alone (one surface), to see where a frame's time goes.
void BM_SampleSurfaceSamba(benchmark::State& state) {
  const SambaFrames* samba = LoadSamba();
  if (samba == nullptr) {
    state.SkipWithError("shared data absent: set MESHVID_SHARED_DATA to the data folder");
    return;
  }
  for (auto _ : state) {
    auto samples = SampleSurface(samba->ref[0], static_cast<std::size_t>(state.range(0)), 1);
    benchmark::DoNotOptimize(samples);
  }
}
BENCHMARK(BM_SampleSurfaceSamba)->Arg(200000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace meshvid

BENCHMARK_MAIN();
