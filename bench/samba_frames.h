// The benchmarks' shared input: samba's first ground-truth frames from the shared data
// (MESHVID_SHARED_DATA, or ../shared/data beside the repository).
#ifndef MESHVID_BENCH_SAMBA_FRAMES_H_
#define MESHVID_BENCH_SAMBA_FRAMES_H_

#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "codec/common/mesh.h"
#include "tools/io/mesh_sequence.h"

namespace meshvid {

/// Samba's first `count` frames and the box bounding them all; `error` says why they could
/// not be loaded (the shared data absent, a bad file), and then the benchmark skips.
struct SambaGroundTruth {
  std::string error;
  std::vector<TriangleMesh> frames;
  Eigen::AlignedBox3f bounds;
};

inline SambaGroundTruth LoadSambaGroundTruth(int count) {
  SambaGroundTruth samba;
  const char* env = std::getenv("MESHVID_SHARED_DATA");
  const std::string data = env != nullptr ? env : MESHVID_DEFAULT_SHARED_DATA;
  const std::string path = data + "/sequences/samba.obj";
  if (!std::filesystem::exists(path)) {
    samba.error = "shared data absent (" + path + "); set MESHVID_SHARED_DATA";
    return samba;
  }
  auto sequence = OpenMeshSequence(path);
  if (!sequence.ok()) {
    samba.error = sequence.status().ToString();
    return samba;
  }
  for (int t = 0; t < count; ++t) {
    auto mesh = (*sequence)->Frame(t);
    if (!mesh.ok()) {
      samba.error = mesh.status().ToString();
      return samba;
    }
    samba.bounds.extend(BoundingBox(*mesh));
    samba.frames.push_back(std::move(*mesh));
  }
  return samba;
}

}  // namespace meshvid

#endif  // MESHVID_BENCH_SAMBA_FRAMES_H_
