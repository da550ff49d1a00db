#include "tools/sim/raycaster.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meshvid {
namespace {

constexpr int kPacket = 16;

std::string EmbreeErrorText(RTCDevice device) {
  const RTCError error = rtcGetDeviceError(device);
  switch (error) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unknown error " + std::to_string(static_cast<int>(error));
  }
}

}  // namespace

struct RayCaster::EmbreeState {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  RTCGeometry geometry = nullptr;
  std::size_t vertex_count = 0;
  std::size_t triangle_count = 0;
  Eigen::AlignedBox3f bounds;  ///< of the current mesh
};

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
  std::unique_ptr<RayCaster> caster(new RayCaster);
  caster->state_ = std::make_unique<EmbreeState>();
  caster->state_->device = rtcNewDevice(nullptr);
  if (caster->state_->device == nullptr) {
    return InternalError("cannot start Embree (ray casting): " + EmbreeErrorText(nullptr));
  }
  return caster;
}

RayCaster::~RayCaster() {
  if (!state_) return;
  if (state_->scene != nullptr) rtcReleaseScene(state_->scene);
  if (state_->geometry != nullptr) rtcReleaseGeometry(state_->geometry);
  if (state_->device != nullptr) rtcReleaseDevice(state_->device);
}

Status RayCaster::SetMesh(const TriangleMesh& mesh) {
  if (mesh.empty()) return InvalidArgumentError("cannot ray-cast an empty mesh");
  EmbreeState& s = *state_;
  const bool reuse = s.geometry != nullptr && s.vertex_count == mesh.vertex_count() &&
                     s.triangle_count == mesh.triangle_count();
  if (!reuse) {
    if (s.scene != nullptr) rtcReleaseScene(s.scene);
    if (s.geometry != nullptr) rtcReleaseGeometry(s.geometry);
    s.scene = rtcNewScene(s.device);
    rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_NONE);
    rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_MEDIUM);
    s.geometry = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (s.scene == nullptr || s.geometry == nullptr) {
      return InternalError("Embree cannot create a scene: " + EmbreeErrorText(s.device));
    }
    // Embree may read 16 bytes from the last vertex: allocate through Embree, which pads.
    void* vertices = rtcSetNewGeometryBuffer(s.geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                             RTC_FORMAT_FLOAT3, sizeof(float) * 3,
                                             mesh.vertex_count());
    void* indices = rtcSetNewGeometryBuffer(s.geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                            RTC_FORMAT_UINT3, sizeof(std::uint32_t) * 3,
                                            mesh.triangle_count());
    if (vertices == nullptr || indices == nullptr) {
      return InternalError("Embree cannot allocate the mesh buffers (" +
                           std::to_string(mesh.vertex_count()) + " vertices): " +
                           EmbreeErrorText(s.device));
    }
    std::memcpy(indices, mesh.triangles.data(), sizeof(std::uint32_t) * 3 * mesh.triangle_count());
    rtcAttachGeometry(s.scene, s.geometry);
    s.vertex_count = mesh.vertex_count();
    s.triangle_count = mesh.triangle_count();
  } else {
    auto* indices = static_cast<std::uint32_t*>(
        rtcGetGeometryBufferData(s.geometry, RTC_BUFFER_TYPE_INDEX, 0));
    std::memcpy(indices, mesh.triangles.data(), sizeof(std::uint32_t) * 3 * mesh.triangle_count());
    rtcUpdateGeometryBuffer(s.geometry, RTC_BUFFER_TYPE_INDEX, 0);
    rtcUpdateGeometryBuffer(s.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
  }
  auto* vertices =
      static_cast<float*>(rtcGetGeometryBufferData(s.geometry, RTC_BUFFER_TYPE_VERTEX, 0));
  std::memcpy(vertices, mesh.positions.data(), sizeof(float) * 3 * mesh.vertex_count());
  s.bounds = BoundingBox(mesh);
  rtcCommitGeometry(s.geometry);
  rtcCommitScene(s.scene);
  if (rtcGetDeviceError(s.device) != RTC_ERROR_NONE) {
    return InternalError("Embree cannot build the ray-casting structure: " +
                         EmbreeErrorText(s.device));
  }
  return Status::Ok();
}

StatusOr<long> RayCaster::Cast(const ViewCalibration& view, RayCastImage* image) const {
  if (!view.intrinsics.has_value()) {
    return InvalidArgumentError("cannot ray-cast a view without intrinsics");
  }
  if (state_->scene == nullptr) return InvalidArgumentError("ray caster has no mesh");
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
  const Eigen::Matrix3f rotation = view.world_from_camera.linear().cast<float>();
  const Eigen::Vector3f origin = view.world_from_camera.translation().cast<float>();
  RTCScene scene = state_->scene;
  int u_begin, u_end, v_begin, v_end;
  PixelWindow(state_->bounds, view, &u_begin, &u_end, &v_begin, &v_end);
  if (u_begin >= u_end || v_begin >= v_end) return 0L;
  std::atomic<long> hits{0};

  tbb::parallel_for(tbb::blocked_range<int>(v_begin, v_end, 4), [&](const tbb::blocked_range<int>& rows) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    RTCRayHit16 packet;
    int valid[kPacket];
    long local_hits = 0;
    for (int v = rows.begin(); v != rows.end(); ++v) {
      for (int u0 = u_begin; u0 < u_end; u0 += kPacket) {
        for (int i = 0; i < kPacket; ++i) {
          const int u = u0 + i;
          valid[i] = u < u_end ? -1 : 0;
          // Direction with unit camera z: the hit distance t is the depth.
          const Eigen::Vector3f dir =
              rotation * Eigen::Vector3f(static_cast<float>((u - k.cx) / k.fx),
                                         static_cast<float>((v - k.cy) / k.fy), 1.0f);
          packet.ray.org_x[i] = origin.x();
          packet.ray.org_y[i] = origin.y();
          packet.ray.org_z[i] = origin.z();
          packet.ray.dir_x[i] = dir.x();
          packet.ray.dir_y[i] = dir.y();
          packet.ray.dir_z[i] = dir.z();
          packet.ray.tnear[i] = 0.0f;
          packet.ray.tfar[i] = std::numeric_limits<float>::infinity();
          packet.ray.time[i] = 0.0f;
          packet.ray.mask[i] = 0xFFFFFFFFu;
          packet.ray.id[i] = static_cast<unsigned>(i);
          packet.ray.flags[i] = 0;
          packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, scene, &context, &packet);
        for (int i = 0; i < kPacket && u0 + i < u_end; ++i) {
          if (packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
          const std::size_t pixel = static_cast<std::size_t>(v) * k.width + u0 + i;
          const Eigen::Vector3f dir(packet.ray.dir_x[i], packet.ray.dir_y[i], packet.ray.dir_z[i]);
          const Eigen::Vector3f normal(packet.hit.Ng_x[i], packet.hit.Ng_y[i], packet.hit.Ng_z[i]);
          const float norms = dir.norm() * normal.norm();
          if (!(norms > 0)) continue;  // degenerate triangle
          image->depth[pixel] = packet.ray.tfar[i];
          image->cos_incidence[pixel] = std::abs(dir.dot(normal)) / norms;
          ++local_hits;
        }
      }
    }
    hits += local_hits;
  });
  return hits.load();
}

}  // namespace meshvid
