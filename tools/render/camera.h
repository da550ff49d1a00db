// The camera of `meshvid render`: a pinhole looking at the subject from an orbit around it
// (y up), placed so the subject's bounds fill the picture.
#ifndef MESHVID_TOOLS_RENDER_CAMERA_H_
#define MESHVID_TOOLS_RENDER_CAMERA_H_

#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "format/status.h"

namespace meshvid {

/// Where the camera sits around the subject.
struct OrbitSpec {
  float azimuth_degrees = 25;    ///< about +y; 0 looks from +z towards -z, 90 from +x
  float elevation_degrees = 12;  ///< above the horizontal plane through the subject's centre
  float zoom = 1;                ///< > 1 comes closer
};

/// Parses "AZ,EL" or "AZ,EL,ZOOM" (degrees, degrees, factor).
StatusOr<OrbitSpec> ParseOrbitSpec(const std::string& text);

/// A pinhole camera: rays from `eye` through pixel centres.
struct RenderCamera {
  int width = 640;
  int height = 480;
  Eigen::Vector3f eye = Eigen::Vector3f::Zero();
  Eigen::Vector3f forward = -Eigen::Vector3f::UnitZ();  ///< unit, towards the subject
  Eigen::Vector3f right = Eigen::Vector3f::UnitX();     ///< unit
  Eigen::Vector3f up = Eigen::Vector3f::UnitY();        ///< unit
  float tan_half_fov_y = 0.4f;

  /// Direction (not unit) of the ray through the centre of pixel (x, y), y down.
  Eigen::Vector3f RayDirection(int x, int y) const {
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const float sx = (2.0f * (x + 0.5f) / width - 1.0f) * tan_half_fov_y * aspect;
    const float sy = (1.0f - 2.0f * (y + 0.5f) / height) * tan_half_fov_y;
    return forward + sx * right + sy * up;
  }
};

/// A camera of `width` x `height` on the orbit `spec` around `bounds`, at the distance where
/// the bounds' enclosing sphere fits the picture (divided by spec.zoom).
RenderCamera FrameBounds(const Eigen::AlignedBox3f& bounds, const OrbitSpec& spec, int width,
                         int height);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_RENDER_CAMERA_H_
