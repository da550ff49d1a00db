// Prints what a .mvid holds and decodes its first frame at the coarsest level: the smallest
// player, linked with meshvid::decoder alone (or `pkg-config --cflags --libs meshvid`).
// Usage: mvid_info FILE.mvid
#include <cstdio>

#include <meshvid/codec/dec/mvid_decoder.h>
#include <meshvid/version.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s FILE.mvid\n", argv[0]);
    return 2;
  }
  auto decoder = meshvid::MvidDecoder::OpenFile(argv[1]);
  if (!decoder.ok()) {
    std::fprintf(stderr, "%s\n", decoder.status().ToString().c_str());
    return 1;
  }
  const meshvid::MvidInfo& info = (*decoder)->info();
  std::printf("meshvid %s: %s: format %u, %u frames at %g frames/s, levels 0..%d\n",
              MESHVID_VERSION_STRING, argv[1], info.format_version, info.frame_count,
              info.frame_rate, info.levels);
  if (info.frame_count == 0) return 0;
  meshvid::StatusOr<meshvid::TriangleMesh> mesh = (*decoder)->DecodeFrame(0, 0);
  if (!mesh.ok()) {
    std::fprintf(stderr, "frame 0: %s\n", mesh.status().ToString().c_str());
    return 1;
  }
  std::printf("frame 0 at level 0: %zu vertices, %zu triangles\n", mesh->vertex_count(),
              mesh->triangle_count());
  return 0;
}
