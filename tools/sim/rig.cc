#include "tools/sim/rig.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace meshvid {

PinholeIntrinsics RigIntrinsics(const RigOptions& options) {
  PinholeIntrinsics k;
  k.width = options.width;
  k.height = options.height;
  if (options.fov_deg > 0) {
    k.fx = 0.5 * options.width / std::tan(0.5 * options.fov_deg * std::numbers::pi / 180.0);
  } else {
    k.fx = 525.0 * options.width / 640.0;
  }
  k.fy = k.fx;
  k.cx = (options.width - 1) / 2.0;
  k.cy = (options.height - 1) / 2.0;
  return k;
}

Eigen::Vector3d UpVector(UpAxis up) {
  return up == UpAxis::kY ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
}

Eigen::Vector3d FrontVector(UpAxis up) {
  return up == UpAxis::kY ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(0, -1, 0);
}

Eigen::Vector3d RigCentreDirection(const RigOptions& options) {
  return Eigen::AngleAxisd(options.azimuth_deg * std::numbers::pi / 180.0, UpVector(options.up)) *
         FrontVector(options.up);
}

double DepthOverWidth(const Eigen::AlignedBox3d& subject, const Eigen::Vector3d& direction,
                      UpAxis up) {
  const Eigen::Vector3d across = UpVector(up).cross(direction);
  const Eigen::Vector3d size = subject.sizes();
  const double depth = size.cwiseProduct(direction.cwiseAbs()).sum();
  const double width = size.cwiseProduct(across.cwiseAbs()).sum();
  return width > 0 ? depth / width : 0.0;
}

StatusOr<std::vector<ViewCalibration>> PlaceCameras(const Eigen::AlignedBox3d& subject,
                                                    const RigOptions& options) {
  if (options.views < 1) {
    return InvalidArgumentError("the rig needs at least one view (got " +
                                std::to_string(options.views) + ")");
  }
  if (options.width < 2 || options.height < 2) {
    return InvalidArgumentError("image size " + std::to_string(options.width) + "x" +
                                std::to_string(options.height) +
                                " is too small (need at least 2x2)");
  }
  if (options.fov_deg < 0 || options.fov_deg >= 179) {
    return InvalidArgumentError("field of view must be in (0, 179) degrees");
  }
  if (subject.isEmpty()) return InvalidArgumentError("the subject's bounding box is empty");
  const PinholeIntrinsics k = RigIntrinsics(options);
  const Eigen::Vector3d centre = subject.center();
  const Eigen::Vector3d up = UpVector(options.up);
  const Eigen::Vector3d front = FrontVector(options.up);
  const double usable = 1.0 - std::clamp(options.margin, 0.0, 0.9);

  std::vector<ViewCalibration> views;
  for (int i = 0; i < options.views; ++i) {
    double degrees = options.layout == RigLayout::kArc
                               ? (i - (options.views - 1) / 2.0) * options.arc_step_deg
                               : 360.0 * i / options.views;
    degrees += options.azimuth_deg;
    const Eigen::Vector3d toward_camera =
        Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, up) * front;
    // Camera frame (OpenCV): z looks at the subject, y points down, x = y cross z.
    Eigen::Matrix3d rotation;
    const Eigen::Vector3d z = -toward_camera;
    const Eigen::Vector3d y = -(up - up.dot(z) * z).normalized();
    rotation.col(0) = y.cross(z);
    rotation.col(1) = y;
    rotation.col(2) = z;
    // Smallest distance from the centre at which every box corner projects inside the usable
    // part of the image: |f * x / (d + z)| <= usable * half-size for every corner.
    double distance = 0;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d p = rotation.transpose() * (subject.corner(
                                    static_cast<Eigen::AlignedBox3d::CornerType>(c)) - centre);
      distance = std::max(distance, k.fx * std::abs(p.x()) / (usable * 0.5 * k.width) - p.z());
      distance = std::max(distance, k.fy * std::abs(p.y()) / (usable * 0.5 * k.height) - p.z());
    }
    // Keep the camera outside the box even for a flat subject.
    distance = std::max(distance, 1e-3 + subject.sizes().norm() * 0.5);
    ViewCalibration view;
    view.intrinsics = k;
    view.world_from_camera.linear() = rotation;
    view.world_from_camera.translation() = centre + distance * toward_camera;
    view.has_extrinsics = true;
    views.push_back(view);
  }
  return views;
}

}  // namespace meshvid
