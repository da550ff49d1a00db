#include "codec/common/embree_scene.h"

#include <embree3/rtcore.h>

#include <cstring>
#include <mutex>
#include <string>

namespace meshvid {
namespace {

/// Owns one reference on an Embree device.
struct DeviceHandle {
  RTCDevice device = nullptr;
  ~DeviceHandle() {
    if (device != nullptr) rtcReleaseDevice(device);
  }
};

/// The device every live scene shares: created by the first scene, released with the last
/// (creating one costs milliseconds, so scenes alive together share it).
StatusOr<std::shared_ptr<DeviceHandle>> AcquireDevice() {
  static std::mutex mutex;
  static std::weak_ptr<DeviceHandle> shared;
  std::lock_guard<std::mutex> lock(mutex);
  if (std::shared_ptr<DeviceHandle> device = shared.lock()) return device;
  auto device = std::make_shared<DeviceHandle>();
  // One instruction set on every machine: Embree otherwise picks the widest the CPU has (SSE,
  // AVX2, AVX-512), and its kernels round differently, so the same capture would encode to
  // other bytes on another machine. SSE4.2 is on every x86-64 CPU since 2008 and costs the
  // encoder and the renderer nothing measurable (bench/ENCODE.md); where Embree cannot use
  // it (another architecture), its own choice stands.
  device->device = rtcNewDevice("verbose=0,isa=sse4.2");
  if (device->device == nullptr || rtcGetDeviceError(device->device) != RTC_ERROR_NONE) {
    if (device->device != nullptr) rtcReleaseDevice(device->device);
    device->device = rtcNewDevice("verbose=0");
  }
  if (device->device == nullptr) {
    return InternalError("Embree could not start (rtcNewDevice failed; unsupported CPU?)");
  }
  shared = device;
  return device;
}

std::string ErrorText(RTCDevice device) {
  switch (rtcGetDeviceError(device)) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unknown error";
  }
}

}  // namespace

struct EmbreeScene::State {
  std::shared_ptr<DeviceHandle> device;
  RTCScene scene = nullptr;
  RTCGeometry geometry = nullptr;
  ~State() {
    if (scene != nullptr) rtcReleaseScene(scene);
    if (geometry != nullptr) rtcReleaseGeometry(geometry);
  }
};

EmbreeScene::~EmbreeScene() = default;

StatusOr<std::unique_ptr<EmbreeScene>> EmbreeScene::Create(const TriangleMesh& mesh) {
  if (mesh.empty()) return InvalidArgumentError("cannot ray-trace an empty mesh");
  std::unique_ptr<EmbreeScene> scene(new EmbreeScene);
  scene->state_ = std::make_unique<State>();
  MESHVID_ASSIGN_OR_RETURN(scene->state_->device, AcquireDevice());
  MESHVID_RETURN_IF_ERROR(scene->Update(mesh));
  return scene;
}

Status EmbreeScene::Update(const TriangleMesh& mesh) {
  if (mesh.empty()) return InvalidArgumentError("cannot ray-trace an empty mesh");
  State& s = *state_;
  RTCDevice device = s.device->device;
  const bool reuse = s.geometry != nullptr && vertex_count_ == mesh.vertex_count() &&
                     triangle_count_ == mesh.triangle_count();
  if (!reuse) {
    if (s.scene != nullptr) rtcReleaseScene(s.scene);
    if (s.geometry != nullptr) rtcReleaseGeometry(s.geometry);
    s.scene = rtcNewScene(device);
    s.geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (s.scene == nullptr || s.geometry == nullptr) {
      return InternalError("Embree cannot create a scene: " + ErrorText(device));
    }
    // Buffers allocated by Embree are padded for its 16-byte vertex loads.
    void* vertices = rtcSetNewGeometryBuffer(s.geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                             RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                             mesh.vertex_count());
    void* indices = rtcSetNewGeometryBuffer(s.geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                            RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t),
                                            mesh.triangle_count());
    if (vertices == nullptr || indices == nullptr) {
      rtcReleaseGeometry(s.geometry);
      s.geometry = nullptr;
      return InternalError("Embree cannot allocate a mesh of " +
                           std::to_string(mesh.triangle_count()) +
                           " triangles: " + ErrorText(device));
    }
    rtcAttachGeometry(s.scene, s.geometry);
    vertex_count_ = mesh.vertex_count();
    triangle_count_ = mesh.triangle_count();
  } else {
    rtcUpdateGeometryBuffer(s.geometry, RTC_BUFFER_TYPE_INDEX, 0);
    rtcUpdateGeometryBuffer(s.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
  }
  std::memcpy(rtcGetGeometryBufferData(s.geometry, RTC_BUFFER_TYPE_VERTEX, 0),
              mesh.positions.data(), 3 * sizeof(float) * mesh.vertex_count());
  std::memcpy(rtcGetGeometryBufferData(s.geometry, RTC_BUFFER_TYPE_INDEX, 0),
              mesh.triangles.data(), 3 * sizeof(std::uint32_t) * mesh.triangle_count());
  rtcCommitGeometry(s.geometry);
  rtcCommitScene(s.scene);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) {
    return InternalError("Embree failed to build the scene of " +
                         std::to_string(mesh.triangle_count()) +
                         " triangles: " + ErrorText(device));
  }
  bounds_ = BoundingBox(mesh);
  return Status::Ok();
}

RayHit EmbreeScene::Intersect(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                              float t_near, float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayhit;
  rayhit.ray.org_x = origin.x();
  rayhit.ray.org_y = origin.y();
  rayhit.ray.org_z = origin.z();
  rayhit.ray.dir_x = direction.x();
  rayhit.ray.dir_y = direction.y();
  rayhit.ray.dir_z = direction.z();
  rayhit.ray.tnear = t_near;
  rayhit.ray.tfar = t_far;
  rayhit.ray.time = 0.0f;
  rayhit.ray.mask = 0xFFFFFFFFu;
  rayhit.ray.id = 0;
  rayhit.ray.flags = 0;
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(state_->scene, &context, &rayhit);
  RayHit hit;
  if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.t = rayhit.ray.tfar;
  hit.normal = Eigen::Vector3f(rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z);
  hit.triangle = rayhit.hit.primID;
  hit.u = rayhit.hit.u;
  hit.v = rayhit.hit.v;
  return hit;
}

void EmbreeScene::IntersectPacket(const RayPacket& packet, RayHit* hits) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  RTCRayHit16 rays;
  // Embree reads the valid mask with aligned vector loads: 64-byte alignment, as the ray
  // packet (without it, rtcIntersect16 faulted under ASan's stack layout).
  alignas(64) int valid[RayPacket::kSize];
  for (int i = 0; i < RayPacket::kSize; ++i) {
    const bool used = i < packet.count;
    valid[i] = used ? -1 : 0;
    const int j = used ? i : 0;  // unused lanes carry a copy of a valid ray
    rays.ray.org_x[i] = packet.origin[j].x();
    rays.ray.org_y[i] = packet.origin[j].y();
    rays.ray.org_z[i] = packet.origin[j].z();
    rays.ray.dir_x[i] = packet.direction[j].x();
    rays.ray.dir_y[i] = packet.direction[j].y();
    rays.ray.dir_z[i] = packet.direction[j].z();
    rays.ray.tnear[i] = 0.0f;
    rays.ray.tfar[i] = packet.t_far[j];
    rays.ray.time[i] = 0.0f;
    rays.ray.mask[i] = 0xFFFFFFFFu;
    rays.ray.id[i] = static_cast<unsigned>(i);
    rays.ray.flags[i] = 0;
    rays.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rays.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, state_->scene, &context, &rays);
  for (int i = 0; i < packet.count; ++i) {
    RayHit& hit = hits[i];
    hit = RayHit();
    if (rays.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
    hit.t = rays.ray.tfar[i];
    hit.normal = Eigen::Vector3f(rays.hit.Ng_x[i], rays.hit.Ng_y[i], rays.hit.Ng_z[i]);
    hit.triangle = rays.hit.primID[i];
    hit.u = rays.hit.u[i];
    hit.v = rays.hit.v[i];
  }
}

namespace {

struct VisitState {
  EmbreeScene::TriangleVisitor visit;
  void* user;
};

bool PointQueryCallback(RTCPointQueryFunctionArguments* args) {
  auto* state = static_cast<VisitState*>(args->userPtr);
  return state->visit(state->user, args->primID, &args->query->radius);
}

}  // namespace

void EmbreeScene::VisitTrianglesNear(const Eigen::Vector3f& point, float radius,
                                     TriangleVisitor visit, void* user) const {
  VisitState state{visit, user};
  RTCPointQuery query;
  query.x = point.x();
  query.y = point.y();
  query.z = point.z();
  query.time = 0.0f;
  query.radius = radius;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(state_->scene, &query, &context, PointQueryCallback, &state);
}

}  // namespace meshvid
