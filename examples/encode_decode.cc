// A capture held in memory (one range view of a moving ellipsoid, 6 frames), encoded into a
// .mvid in memory with meshvid::encoder and decoded back with meshvid::decoder. Prints the
// file's size and each decoded frame's distance to the ellipsoid; exits 1 if anything fails, a
// frame decodes farther than 0.5% of the object's size from it, or the frames do not share
// their triangles (one key group).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <span>
#include <vector>

#include <meshvid/codec/dec/mvid_decoder.h>
#include <meshvid/codec/enc/encoder.h>
#include <meshvid/codec/enc/frame_source.h>
#include <meshvid/version.h>

namespace {

const Eigen::Vector3f kRadii(0.6f, 0.4f, 0.3f);

/// The ellipsoid of radii kRadii as a latitude-longitude mesh, centred at `centre`.
meshvid::TriangleMesh Ellipsoid(const Eigen::Vector3f& centre) {
  constexpr int kRings = 32, kSegments = 64;
  meshvid::TriangleMesh mesh;
  const auto at = [](int ring, int segment) {
    return static_cast<std::uint32_t>(1 + (ring - 1) * kSegments + segment % kSegments);
  };
  mesh.positions.push_back(centre + Eigen::Vector3f(0, kRadii.y(), 0));
  for (int r = 1; r <= kRings; ++r) {
    const double theta = M_PI * r / (kRings + 1);
    for (int s = 0; s < kSegments; ++s) {
      const double phi = 2 * M_PI * s / kSegments;
      const Eigen::Vector3f unit(std::sin(theta) * std::cos(phi), std::cos(theta),
                                 -std::sin(theta) * std::sin(phi));
      mesh.positions.push_back(centre + unit.cwiseProduct(kRadii));
    }
  }
  mesh.positions.push_back(centre - Eigen::Vector3f(0, kRadii.y(), 0));
  const auto south = static_cast<std::uint32_t>(mesh.positions.size() - 1);
  for (int s = 0; s < kSegments; ++s) {
    mesh.triangles.emplace_back(0, at(1, s), at(1, s + 1));
    for (int r = 1; r < kRings; ++r) {
      mesh.triangles.emplace_back(at(r, s), at(r + 1, s), at(r + 1, s + 1));
      mesh.triangles.emplace_back(at(r, s), at(r + 1, s + 1), at(r, s + 1));
    }
    mesh.triangles.emplace_back(at(kRings, s), south, at(kRings, s + 1));
  }
  return mesh;
}

/// Root mean square distance of the decoded vertices to the ellipsoid centred at `centre`,
/// measured along the ray from its centre (an upper bound of the distance to the surface).
double RmsDistance(const meshvid::TriangleMesh& decoded, const Eigen::Vector3f& centre) {
  double sum = 0;
  for (const Eigen::Vector3f& p : decoded.positions) {
    const Eigen::Vector3f offset = p - centre;
    const float scaled = offset.cwiseQuotient(kRadii).norm();  // 1 on the surface
    const double error = scaled > 0 ? offset.norm() * std::abs(1 - 1 / scaled) : kRadii.minCoeff();
    sum += error * error;
  }
  return std::sqrt(sum / std::max<std::size_t>(1, decoded.positions.size()));
}

}  // namespace

int main() {
  std::printf("meshvid %s\n", MESHVID_VERSION_STRING);

  // The capture: frames[frame][view], one view per frame, the ellipsoid rising 1 cm a frame.
  constexpr int kFrames = 6;
  const auto centre = [](int frame) { return Eigen::Vector3f(0, 0.01f * frame, 0); };
  std::vector<std::vector<meshvid::TriangleMesh>> frames;
  for (int f = 0; f < kFrames; ++f) frames.push_back({Ellipsoid(centre(f))});
  meshvid::StatusOr<meshvid::MemoryFrameSource> source =
      meshvid::MemoryFrameSource::Create(std::move(frames), /*frame_rate=*/30);
  if (!source.ok()) {
    std::fprintf(stderr, "capture: %s\n", source.status().ToString().c_str());
    return 1;
  }

  // Encode into memory: the sink receives the file's bytes in order.
  meshvid::EncoderOptions options;
  options.levels = 1;
  options.base_vertices = 600;
  options.codec = meshvid::VideoCodec::kFfv1;  // lossless displacements; AV1 is the default
  options.max_key_groups = 1;  // one base, so every frame has the same triangles
  std::vector<std::uint8_t> file;
  const meshvid::ByteSink sink = [&file](std::span<const std::uint8_t> bytes) {
    file.insert(file.end(), bytes.begin(), bytes.end());
    return meshvid::Status::Ok();
  };
  meshvid::StatusOr<meshvid::EncodeSummary> summary =
      meshvid::EncodeCapture(*source, sink, options);
  if (!summary.ok()) {
    std::fprintf(stderr, "encode: %s\n", summary.status().ToString().c_str());
    return 1;
  }
  std::printf("encoded %d frames into %zu bytes (key groups: %zu, base vertices: %zu)\n",
              summary->frames, file.size(), summary->key_groups.size(), summary->base_vertices);

  // Decode every frame at the finest level.
  auto decoder = meshvid::MvidDecoder::OpenMemory(std::move(file));
  if (!decoder.ok()) {
    std::fprintf(stderr, "open: %s\n", decoder.status().ToString().c_str());
    return 1;
  }
  const int level = (*decoder)->info().levels;
  bool close = (*decoder)->info().frame_count == kFrames;
  std::size_t triangles = 0;  // one key group: the same triangles in every frame
  for (std::uint32_t f = 0; f < (*decoder)->info().frame_count; ++f) {
    meshvid::StatusOr<meshvid::TriangleMesh> mesh = (*decoder)->DecodeFrame(f, level);
    if (!mesh.ok()) {
      std::fprintf(stderr, "decode frame %u: %s\n", f, mesh.status().ToString().c_str());
      return 1;
    }
    const double rms = RmsDistance(*mesh, centre(f));
    std::printf("frame %u: %zu vertices, %zu triangles, RMS distance to the ellipsoid %.4f\n", f,
                mesh->vertex_count(), mesh->triangle_count(), rms);
    close = close && rms < 0.005 * 1.2;  // 0.5% of the ellipsoid's largest extent (1.2)
    if (f == 0) triangles = mesh->triangle_count();
    close = close && mesh->triangle_count() == triangles;
  }
  if (!close) {
    std::fprintf(stderr, "the decoded frames are not the capture's\n");
    return 1;
  }
  return 0;
}
