// Fuzz target: capture manifests (spec/capture-manifest.md) through CaptureSequence::Open,
// then the first view of the first frame. The reader takes a path: the input is written as
// manifest.json to a scratch folder that also holds a one-triangle view.ply and a 2x2 16-bit
// depth view.png, which manifests may name.
// Invariants: clean errors; an opened capture has at least one frame and one view.
#include <string>

#include "tests/fuzz/fuzz_util.h"
#include "tools/io/capture.h"
#include "tools/io/depth_image.h"
#include "tools/io/mesh_io.h"

using namespace meshvid;

namespace {

/// Writes the view files once per process.
void WriteViewFiles() {
  static const bool written = [] {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
    mesh.triangles = {Triangle(0, 1, 2)};
    if (!WriteMesh(fuzz::ScratchDir() + "/view.ply", mesh).ok()) fuzz::Fail("view.ply");
    DepthImage depth;
    depth.width = depth.height = 2;
    depth.values = {1000, 1000, 1000, 1000};
    if (!WriteDepthPng(fuzz::ScratchDir() + "/view.png", depth).ok()) fuzz::Fail("view.png");
    return true;
  }();
  (void)written;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  WriteViewFiles();
  const std::string path = fuzz::WriteScratchFile("manifest.json", {data, size});
  StatusOr<std::unique_ptr<CaptureSequence>> capture = CaptureSequence::Open(path);
  if (!capture.ok()) {
    fuzz::ExpectCleanError(capture.status());
    return 0;
  }
  if ((*capture)->frame_count() < 1 || (*capture)->view_count() < 1) {
    fuzz::Fail("an opened capture without frames or views");
  }
  fuzz::ExpectCleanError((*capture)->LoadView(0, 0).status());
  return 0;
}
