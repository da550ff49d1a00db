#include "codec/enc/normal_shooting.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <cstring>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meshvid {
namespace {

/// One Embree device for the process: creating a device costs milliseconds and its thread
/// pool is shared by every scene.
RTCDevice SharedDevice() {
  static RTCDevice device = rtcNewDevice("verbose=0");
  return device;
}

/// Distance to the first hit along `direction` within (0, max_t] with an acceptable angle, or
/// infinity; `normal` receives the unnormalised normal of the triangle hit.
float FirstHit(RTCScene scene, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
               float max_t, float min_abs_cos, Eigen::Vector3f* normal_out) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayhit;
  rayhit.ray.org_x = origin.x();
  rayhit.ray.org_y = origin.y();
  rayhit.ray.org_z = origin.z();
  rayhit.ray.dir_x = direction.x();
  rayhit.ray.dir_y = direction.y();
  rayhit.ray.dir_z = direction.z();
  rayhit.ray.tnear = 0.0f;
  rayhit.ray.tfar = max_t;
  rayhit.ray.time = 0.0f;
  rayhit.ray.mask = 0xFFFFFFFFu;
  rayhit.ray.id = 0;
  rayhit.ray.flags = 0;
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &context, &rayhit);
  if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::numeric_limits<float>::infinity();
  const Eigen::Vector3f normal(rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z);
  const float denominator = normal.norm() * direction.norm();
  if (!(denominator > 0)) return std::numeric_limits<float>::infinity();
  const float abs_cos = std::abs(normal.dot(direction)) / denominator;
  if (abs_cos < min_abs_cos) return std::numeric_limits<float>::infinity();
  *normal_out = normal;
  return rayhit.ray.tfar;
}

}  // namespace

struct ShootingTarget::Embree {
  RTCScene scene = nullptr;
  ~Embree() {
    if (scene != nullptr) rtcReleaseScene(scene);
  }
};

ShootingTarget::~ShootingTarget() = default;

StatusOr<std::unique_ptr<ShootingTarget>> ShootingTarget::Create(const TriangleMesh& mesh) {
  if (mesh.empty()) return InvalidArgumentError("cannot shoot rays at an empty mesh");
  RTCDevice device = SharedDevice();
  if (device == nullptr) return InternalError("Embree could not start (rtcNewDevice failed)");
  std::unique_ptr<ShootingTarget> target(new ShootingTarget);
  target->embree_ = std::make_unique<Embree>();
  RTCScene scene = rtcNewScene(device);
  target->embree_->scene = scene;
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Buffers allocated by Embree are padded for its 16-byte vertex loads.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
      mesh.vertex_count()));
  auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t),
      mesh.triangle_count()));
  if (vertices == nullptr || indices == nullptr) {
    rtcReleaseGeometry(geometry);
    return InternalError("Embree cannot allocate a mesh of " +
                         std::to_string(mesh.triangle_count()) + " triangles");
  }
  std::memcpy(vertices, mesh.positions.data(), 3 * sizeof(float) * mesh.vertex_count());
  std::memcpy(indices, mesh.triangles.data(), 3 * sizeof(std::uint32_t) * mesh.triangle_count());
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) {
    return InternalError("Embree failed to build the scene of a mesh");
  }
  target->triangle_count_ = mesh.triangle_count();
  return target;
}

ShotHit ShootingTarget::ShootHit(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                                 const ShotLimits& limits) const {
  Eigen::Vector3f forward_normal, backward_normal;
  const float forward = FirstHit(embree_->scene, origin, direction, limits.max_distance,
                                 limits.min_abs_cos, &forward_normal);
  const float backward =
      FirstHit(embree_->scene, origin, -direction, std::min(forward, limits.max_distance),
               limits.min_abs_cos, &backward_normal);
  ShotHit hit;
  if (std::isinf(forward) && std::isinf(backward)) return hit;
  if (forward <= backward) {
    hit.distance = forward;
    hit.normal = forward_normal.normalized();
  } else {
    hit.distance = -backward;
    hit.normal = backward_normal.normalized();
  }
  return hit;
}

float ShootingTarget::Shoot(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                            const ShotLimits& limits) const {
  return ShootHit(origin, direction, limits).distance;
}

void ShootingTarget::ShootAll(std::span<const Eigen::Vector3f> origins,
                              std::span<const Eigen::Vector3f> directions,
                              const ShotLimits& limits, std::vector<float>* distances) const {
  distances->resize(origins.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, origins.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i) {
                        (*distances)[i] = Shoot(origins[i], directions[i], limits);
                      }
                    });
}

}  // namespace meshvid
