// Mesh I/O speed: binary/ascii PLY write and read of a ~100k-vertex mesh, range-grid meshing of
// a 640x480 depth frame, and reading the samba template OBJ from the shared data.
#include <cmath>
#include <sstream>
#include <string>

#include <benchmark/benchmark.h>

#include "tools/io/mesh_io.h"
#include "tools/io/range_grid.h"

namespace meshvid {
namespace {

// A 640 x 480 range grid of a wavy surface 2 m away, with a hole and a depth step.
RangeGrid MakeRangeGrid() {
  RangeGrid grid;
  grid.width = 640;
  grid.height = 480;
  for (int r = 0; r < grid.height; ++r) {
    for (int c = 0; c < grid.width; ++c) {
      float depth = 2.0f + 0.05f * std::sin(c * 0.05f) * std::cos(r * 0.04f);
      if (c > 400) depth += 0.5f;
      if ((c - 200) * (c - 200) + (r - 240) * (r - 240) < 900) depth = 0;
      grid.points.emplace_back((c - 320) * depth / 500.0f, (r - 240) * depth / 500.0f, depth);
      grid.depth.push_back(depth);
    }
  }
  return grid;
}

// ~100k vertices, ~200k triangles, with normals.
TriangleMesh MakeLargeMesh() {
  RangeGrid grid = MakeRangeGrid();
  grid.width = 320;
  grid.height = 320;
  grid.points.resize(320 * 320);
  grid.depth.resize(320 * 320);
  for (float& d : grid.depth) d = 2.0f;
  TriangleMesh mesh = TriangulateRangeGrid(grid, {1e9f});
  mesh.normals = ComputeVertexNormals(mesh);
  return mesh;
}

void BM_WritePly(benchmark::State& state) {
  const TriangleMesh mesh = MakeLargeMesh();
  MeshWriteOptions options;
  options.ply_encoding = state.range(0) ? PlyEncoding::kAscii : PlyEncoding::kBinaryLittleEndian;
  for (auto _ : state) {
    std::ostringstream out;
    if (!WritePly(out, mesh, options).ok()) state.SkipWithError("write failed");
    benchmark::DoNotOptimize(out.str().size());
  }
  state.counters["vertices"] = static_cast<double>(mesh.vertex_count());
}
BENCHMARK(BM_WritePly)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_ReadPly(benchmark::State& state) {
  const TriangleMesh mesh = MakeLargeMesh();
  MeshWriteOptions options;
  options.ply_encoding = state.range(0) ? PlyEncoding::kAscii : PlyEncoding::kBinaryLittleEndian;
  std::ostringstream out;
  if (!WritePly(out, mesh, options).ok()) state.SkipWithError("write failed");
  const std::string data = out.str();
  for (auto _ : state) {
    std::istringstream in(data);
    auto read = ReadPly(in, "bench.ply");
    if (!read.ok()) state.SkipWithError(read.status().ToString().c_str());
    benchmark::DoNotOptimize(read->positions.data());
  }
  state.counters["vertices"] = static_cast<double>(mesh.vertex_count());
}
BENCHMARK(BM_ReadPly)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_TriangulateRangeGrid(benchmark::State& state) {
  const RangeGrid grid = MakeRangeGrid();
  std::size_t triangles = 0;
  for (auto _ : state) {
    TriangleMesh mesh = TriangulateRangeGrid(grid);
    triangles = mesh.triangle_count();
    benchmark::DoNotOptimize(mesh.positions.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_TriangulateRangeGrid)->Unit(benchmark::kMillisecond);

void BM_ReadSambaObj(benchmark::State& state) {
  const std::string path = std::string(MESHVID_DEFAULT_SHARED_DATA) + "/sequences/samba.obj";
  for (auto _ : state) {
    auto mesh = ReadMesh(path);
    if (!mesh.ok()) {
      state.SkipWithError(mesh.status().ToString().c_str());
      break;
    }
    benchmark::DoNotOptimize(mesh->positions.data());
  }
}
BENCHMARK(BM_ReadSambaObj)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshvid

BENCHMARK_MAIN();
