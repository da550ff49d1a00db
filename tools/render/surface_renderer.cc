#include "tools/render/surface_renderer.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meshvid {
namespace {

const Eigen::Vector3f kClay(0.78f, 0.76f, 0.72f);

std::uint8_t ToByte(float value) {
  return static_cast<std::uint8_t>(std::clamp(value, 0.0f, 1.0f) * 255.0f + 0.5f);
}

}  // namespace

Rgb BackgroundColour(int y, int height) {
  const float t = height > 1 ? static_cast<float>(y) / static_cast<float>(height - 1) : 0.0f;
  return {ToByte(0.20f + 0.12f * t), ToByte(0.22f + 0.12f * t), ToByte(0.26f + 0.12f * t)};
}

Status SurfaceRenderer::SetMesh(const TriangleMesh& mesh, std::vector<Eigen::Vector3f> colours) {
  if (!colours.empty() && colours.size() != mesh.vertex_count()) {
    return InvalidArgumentError("render: " + std::to_string(colours.size()) +
                                " colours for " + std::to_string(mesh.vertex_count()) +
                                " vertices");
  }
  if (scene_ == nullptr) {
    MESHVID_ASSIGN_OR_RETURN(scene_, EmbreeScene::Create(mesh));
  } else {
    MESHVID_RETURN_IF_ERROR(scene_->Update(mesh));
  }
  triangles_ = mesh.triangles;
  ComputeVertexNormals(mesh.positions, mesh.triangles, &normals_);
  colours_ = std::move(colours);
  return Status::Ok();
}

RgbImage SurfaceRenderer::Render(const RenderCamera& camera) const {
  RgbImage image(camera.width, camera.height);
  // A key light above and left of the camera, a weaker fill from the right.
  const Eigen::Vector3f key = (-camera.forward + 0.6f * camera.up - 0.4f * camera.right).normalized();
  const Eigen::Vector3f fill = (-camera.forward + 0.8f * camera.right).normalized();
  tbb::parallel_for(tbb::blocked_range<int>(0, camera.height, 4), [&](const tbb::blocked_range<int>& rows) {
    RayPacket packet;
    RayHit hits[RayPacket::kSize];
    for (int y = rows.begin(); y != rows.end(); ++y) {
      const Rgb background = BackgroundColour(y, camera.height);
      for (int x0 = 0; x0 < camera.width; x0 += RayPacket::kSize) {
        packet.count = std::min(RayPacket::kSize, camera.width - x0);
        for (int i = 0; i < packet.count; ++i) {
          packet.origin[i] = camera.eye;
          packet.direction[i] = camera.RayDirection(x0 + i, y);
          packet.t_far[i] = std::numeric_limits<float>::infinity();
        }
        if (scene_ != nullptr) scene_->IntersectPacket(packet, hits);
        for (int i = 0; i < packet.count; ++i) {
          if (scene_ == nullptr || !hits[i].hit()) {
            image.Set(x0 + i, y, background);
            continue;
          }
          const Triangle& tri = triangles_[hits[i].triangle];
          const float u = hits[i].u, v = hits[i].v, w = 1.0f - u - v;
          Eigen::Vector3f normal = w * normals_[tri[0]] + u * normals_[tri[1]] + v * normals_[tri[2]];
          if (!(normal.squaredNorm() > 1e-12f)) normal = hits[i].normal;
          normal.normalize();
          const Eigen::Vector3f view = -packet.direction[i].normalized();
          if (normal.dot(view) < 0) normal = -normal;  // two-sided: range scans have backs
          Eigen::Vector3f albedo = kClay;
          if (!colours_.empty()) {
            albedo = w * colours_[tri[0]] + u * colours_[tri[1]] + v * colours_[tri[2]];
          }
          const float diffuse = 0.75f * std::max(0.0f, normal.dot(key)) +
                                0.25f * std::max(0.0f, normal.dot(fill));
          const Eigen::Vector3f half = (key + view).normalized();
          const float specular = 0.18f * std::pow(std::max(0.0f, normal.dot(half)), 40.0f);
          const Eigen::Vector3f c = albedo * (0.22f + 0.85f * diffuse) +
                                    Eigen::Vector3f::Constant(specular);
          image.Set(x0 + i, y, {ToByte(c.x()), ToByte(c.y()), ToByte(c.z())});
        }
      }
    }
  });
  return image;
}

}  // namespace meshvid
