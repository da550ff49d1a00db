// Range-camera calibration shared by capture input, the simulator and depth-image meshing.
// Convention (OpenCV): the camera looks along +z, x to the right, y down in the image.
#ifndef MESHVID_CODEC_COMMON_CAMERA_H_
#define MESHVID_CODEC_COMMON_CAMERA_H_

#include <optional>

#include <Eigen/Geometry>

namespace meshvid {

/// Pinhole intrinsics in pixels. As in OpenCV, the centre of pixel (u, v) is at (u, v), so a
/// centred principal point is cx = (width - 1) / 2.
struct PinholeIntrinsics {
  int width = 0;
  int height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;

  /// Unit-depth ray direction (camera frame, z = 1) through pixel (u, v).
  Eigen::Vector3d RayThrough(double u, double v) const {
    return Eigen::Vector3d((u - cx) / fx, (v - cy) / fy, 1.0);
  }
  /// Projects a camera-frame point (z > 0) to pixel coordinates.
  Eigen::Vector2d Project(const Eigen::Vector3d& p) const {
    return Eigen::Vector2d(fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy);
  }
};

/// The calibration of one view: optional intrinsics and the camera's pose in the world.
struct ViewCalibration {
  std::optional<PinholeIntrinsics> intrinsics;
  /// Maps camera-frame points to world points (the camera's pose). Identity if unknown.
  Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
  bool has_extrinsics = false;

  /// Whether points can be projected into this view's image: intrinsics with a positive
  /// image size and focal lengths, and a known pose.
  bool CanProject() const {
    return intrinsics && has_extrinsics && intrinsics->width > 0 && intrinsics->height > 0 &&
           intrinsics->fx > 0 && intrinsics->fy > 0;
  }
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_CAMERA_H_
