#include "tools/render/camera.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace meshvid {

StatusOr<OrbitSpec> ParseOrbitSpec(const std::string& text) {
  std::vector<float> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      values.push_back(std::stof(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      return InvalidArgumentError("'" + text + "' is not AZ,EL or AZ,EL,ZOOM (numbers)");
    }
  }
  if (values.size() < 2 || values.size() > 3) {
    return InvalidArgumentError("'" + text + "' is not AZ,EL or AZ,EL,ZOOM");
  }
  OrbitSpec spec;
  spec.azimuth_degrees = values[0];
  spec.elevation_degrees = values[1];
  if (values.size() == 3) spec.zoom = values[2];
  if (!(spec.zoom > 0) || std::abs(spec.elevation_degrees) >= 90) {
    return InvalidArgumentError("'" + text + "': the zoom must be positive and the elevation "
                                "within (-90, 90) degrees");
  }
  return spec;
}

RenderCamera FrameBounds(const Eigen::AlignedBox3f& bounds, const OrbitSpec& spec, int width,
                         int height) {
  RenderCamera camera;
  camera.width = width;
  camera.height = height;
  constexpr float kDegrees = 3.14159265358979f / 180.0f;
  const float azimuth = spec.azimuth_degrees * kDegrees;
  const float elevation = spec.elevation_degrees * kDegrees;
  const Eigen::Vector3f towards_eye(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                                    std::cos(elevation) * std::cos(azimuth));
  const Eigen::Vector3f centre =
      bounds.isEmpty() ? Eigen::Vector3f(Eigen::Vector3f::Zero()) : Eigen::Vector3f(bounds.center());
  const float radius =
      bounds.isEmpty() ? 1.0f : std::max(0.5f * bounds.diagonal().norm(), 1e-6f);
  camera.tan_half_fov_y = std::tan(0.5f * 40.0f * kDegrees);  // 40 degrees vertically
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const float tan_half = camera.tan_half_fov_y * std::min(1.0f, aspect);
  const float half_angle = std::atan(tan_half);
  const float distance = 1.02f * radius / std::sin(half_angle) / spec.zoom;
  camera.eye = centre + distance * towards_eye;
  camera.forward = -towards_eye;
  camera.right = camera.forward.cross(Eigen::Vector3f::UnitY()).normalized();
  camera.up = camera.right.cross(camera.forward).normalized();
  return camera;
}

}  // namespace meshvid
