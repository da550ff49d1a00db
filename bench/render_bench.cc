// Speed of `meshvid render`'s core at 640x480: per frame, the BVH rebuilt for the new
// positions (SurfaceRenderer::SetMesh: EmbreeScene::Update, vertex normals) and the picture
// ray-cast and shaded (SurfaceRenderer::Render), on samba's ground truth (9,971 vertices);
// and the same with the surface coloured by distance to the next frame (the --error-against
// path: distances, colours, render).
//   build/bench/render_bench [--benchmark_filter=...]
// Needs the shared data (MESHVID_SHARED_DATA or ../shared/data); skips otherwise.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/samba_frames.h"
#include "tools/eval/surface_distance.h"
#include "tools/io/mesh_sequence.h"
#include "tools/render/camera.h"
#include "tools/render/error_colours.h"
#include "tools/render/surface_renderer.h"

namespace meshvid {
namespace {

constexpr int kFrames = 25;  // samba frames kept in memory for the loop

/// Samba's first frames and the default camera framing them, loaded once.
struct SambaFrames {
  std::string error;
  std::vector<TriangleMesh> frames;
  RenderCamera camera;

  SambaFrames() {
    SambaGroundTruth truth = LoadSambaGroundTruth(kFrames);
    error = std::move(truth.error);
    frames = std::move(truth.frames);
    if (error.empty()) camera = FrameBounds(truth.bounds, OrbitSpec{}, 640, 480);
  }
};

const SambaFrames& Samba() {
  static const SambaFrames* samba = new SambaFrames;
  return *samba;
}

/// BVH update + ray casting + shading, one 640x480 picture per frame.
void BM_SambaRender640x480(benchmark::State& state) {
  const SambaFrames& samba = Samba();
  if (!samba.error.empty()) return state.SkipWithError(samba.error.c_str());
  SurfaceRenderer renderer;
  int t = 0;
  for (auto _ : state) {
    if (!renderer.SetMesh(samba.frames[t % kFrames]).ok()) {
      return state.SkipWithError("SetMesh failed");
    }
    RgbImage image = renderer.Render(samba.camera);
    benchmark::DoNotOptimize(image.pixels.data());
    ++t;
  }
  state.counters["frames/s"] = benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
}

/// As above, coloured by every vertex's distance to the next frame (BVH of it included).
void BM_SambaRenderErrorColours640x480(benchmark::State& state) {
  const SambaFrames& samba = Samba();
  if (!samba.error.empty()) return state.SkipWithError(samba.error.c_str());
  SurfaceRenderer renderer;
  int t = 0;
  for (auto _ : state) {
    const TriangleMesh& mesh = samba.frames[t % kFrames];
    auto reference = SurfaceDistance::Build(samba.frames[(t + 1) % kFrames]);
    if (!reference.ok()) return state.SkipWithError("SurfaceDistance failed");
    const std::vector<float> distances = VertexDistances(mesh, **reference);
    if (!renderer.SetMesh(mesh, ErrorColours(distances, 0.02f)).ok()) {
      return state.SkipWithError("SetMesh failed");
    }
    RgbImage image = renderer.Render(samba.camera);
    benchmark::DoNotOptimize(image.pixels.data());
    ++t;
  }
  state.counters["frames/s"] = benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_SambaRender640x480)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SambaRenderErrorColours640x480)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace meshvid

BENCHMARK_MAIN();
