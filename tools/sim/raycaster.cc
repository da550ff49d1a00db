#include "tools/sim/raycaster.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meshvid {
namespace {

/// The pixel rows/columns [u0, u1) x [v0, v1) outside which no ray can meet `bounds`: the
/// image rectangle around the projection of its corners (the whole image if a corner is
/// not in front of the camera).
void PixelWindow(const Eigen::AlignedBox3f& bounds, const ViewCalibration& view, int* u0,
                 int* u1, int* v0, int* v1) {
  const PinholeIntrinsics& k = *view.intrinsics;
  *u0 = 0, *u1 = k.width, *v0 = 0, *v1 = k.height;
  const Eigen::Isometry3d camera_from_world = view.world_from_camera.inverse();
  double min_u = 1e300, max_u = -1e300, min_v = 1e300, max_v = -1e300;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p =
        camera_from_world *
        bounds.corner(static_cast<Eigen::AlignedBox3f::CornerType>(c)).cast<double>();
    if (!(p.z() > 1e-6)) return;
    const Eigen::Vector2d pixel = k.Project(p);
    min_u = std::min(min_u, pixel.x());
    max_u = std::max(max_u, pixel.x());
    min_v = std::min(min_v, pixel.y());
    max_v = std::max(max_v, pixel.y());
  }
  // One pixel of slack on each side covers rounding in the ray directions.
  auto clamp = [](double x, int hi) { return static_cast<int>(std::clamp(x, 0.0, double(hi))); };
  *u0 = clamp(std::floor(min_u) - 1, k.width);
  *u1 = clamp(std::ceil(max_u) + 2, k.width);
  *v0 = clamp(std::floor(min_v) - 1, k.height);
  *v1 = clamp(std::ceil(max_v) + 2, k.height);
}

}  // namespace

StatusOr<std::unique_ptr<RayCaster>> RayCaster::Create() {
  return std::unique_ptr<RayCaster>(new RayCaster);
}

RayCaster::~RayCaster() = default;

Status RayCaster::SetMesh(const TriangleMesh& mesh) {
  if (mesh.empty()) return InvalidArgumentError("cannot ray-cast an empty mesh");
  colours_ = mesh.colours;
  if (colours_.empty()) {
    triangles_.clear();
  } else {
    triangles_ = mesh.triangles;
  }
  if (scene_ == nullptr) {
    MESHVID_ASSIGN_OR_RETURN(scene_, EmbreeScene::Create(mesh));
    return Status::Ok();
  }
  return scene_->Update(mesh);
}

StatusOr<long> RayCaster::Cast(const ViewCalibration& view, RayCastImage* image) const {
  if (!view.intrinsics.has_value()) {
    return InvalidArgumentError("cannot ray-cast a view without intrinsics");
  }
  if (scene_ == nullptr) return InvalidArgumentError("ray caster has no mesh");
  const PinholeIntrinsics& k = *view.intrinsics;
  if (k.width < 1 || k.height < 1 || !(k.fx > 0) || !(k.fy > 0)) {
    return InvalidArgumentError("bad intrinsics: image " + std::to_string(k.width) + "x" +
                                std::to_string(k.height) + ", focal lengths must be positive");
  }
  image->width = k.width;
  image->height = k.height;
  const std::size_t pixels = static_cast<std::size_t>(k.width) * k.height;
  image->depth.assign(pixels, 0.0f);
  image->cos_incidence.assign(pixels, 0.0f);
  const bool coloured = !colours_.empty();
  image->colour.assign(coloured ? pixels : 0, Eigen::Vector3f::Zero());
  const Eigen::Matrix3f rotation = view.world_from_camera.linear().cast<float>();
  const Eigen::Vector3f origin = view.world_from_camera.translation().cast<float>();
  int u_begin, u_end, v_begin, v_end;
  PixelWindow(scene_->bounds(), view, &u_begin, &u_end, &v_begin, &v_end);
  if (u_begin >= u_end || v_begin >= v_end) return 0L;
  std::atomic<long> hits{0};

  tbb::parallel_for(tbb::blocked_range<int>(v_begin, v_end, 4), [&](const tbb::blocked_range<int>& rows) {
    RayPacket packet;
    RayHit packet_hits[RayPacket::kSize];
    long local_hits = 0;
    for (int v = rows.begin(); v != rows.end(); ++v) {
      for (int u0 = u_begin; u0 < u_end; u0 += RayPacket::kSize) {
        packet.count = std::min(RayPacket::kSize, u_end - u0);
        for (int i = 0; i < packet.count; ++i) {
          const int u = u0 + i;
          // Direction with unit camera z: the hit distance t is the depth.
          packet.origin[i] = origin;
          packet.direction[i] =
              rotation * Eigen::Vector3f(static_cast<float>((u - k.cx) / k.fx),
                                         static_cast<float>((v - k.cy) / k.fy), 1.0f);
          packet.t_far[i] = std::numeric_limits<float>::infinity();
        }
        scene_->IntersectPacket(packet, packet_hits);
        for (int i = 0; i < packet.count; ++i) {
          const RayHit& hit = packet_hits[i];
          if (!hit.hit()) continue;
          const std::size_t pixel = static_cast<std::size_t>(v) * k.width + u0 + i;
          const Eigen::Vector3f& dir = packet.direction[i];
          const float norms = dir.norm() * hit.normal.norm();
          if (!(norms > 0)) continue;  // degenerate triangle
          image->depth[pixel] = hit.t;
          image->cos_incidence[pixel] = std::abs(dir.dot(hit.normal)) / norms;
          if (coloured) {
            image->colour[pixel] = BlendColours(colours_, triangles_[hit.triangle], hit.u, hit.v);
          }
          ++local_hits;
        }
      }
    }
    hits += local_hits;
  });
  return hits.load();
}

}  // namespace meshvid
