// Placement of the simulated range cameras around the subject.
#ifndef MESHVID_TOOLS_SIM_RIG_H_
#define MESHVID_TOOLS_SIM_RIG_H_

#include <vector>

#include <Eigen/Geometry>

#include "codec/common/camera.h"
#include "format/status.h"

namespace meshvid {

/// How the views are spread around the subject.
enum class RigLayout {
  kArc,   ///< a frontal arc, views `arc_step_deg` apart, centred on the subject's front
  kRing,  ///< views evenly spread over 360 degrees, the first facing the subject's front
};

/// The data's up axis; the subject's front is +z for y-up data and -y for z-up data.
enum class UpAxis { kY, kZ };

/// The rig's layout and sensor.
struct RigOptions {
  int views = 3;
  RigLayout layout = RigLayout::kArc;
  double arc_step_deg = 40.0;
  /// Turns the whole rig about the up axis by this many degrees (right-handed), for data
  /// whose subject does not face the default front (samba's dancer mostly faces +x: 90).
  double azimuth_deg = 0.0;
  UpAxis up = UpAxis::kY;
  int width = 640;
  int height = 480;
  /// Horizontal field of view in degrees; 0 uses a Kinect-like focal length (fx = fy = 525
  /// pixels at 640 pixels wide, scaled with the width).
  double fov_deg = 0.0;
  /// Share of the half image kept free around the subject's projected bounding box.
  double margin = 0.05;
};

/// Pinhole intrinsics of the rig's sensor: square pixels, centred principal point.
PinholeIntrinsics RigIntrinsics(const RigOptions& options);

/// The unit "up" and "front" (direction from the subject towards its front) of `up`.
Eigen::Vector3d UpVector(UpAxis up);
Eigen::Vector3d FrontVector(UpAxis up);

/// The unit direction from the subject towards the rig's centre: the arc's middle, or the
/// ring's first view (the front turned by azimuth_deg about the up axis).
Eigen::Vector3d RigCentreDirection(const RigOptions& options);

/// How a box is seen from `direction` (horizontal, unit): its horizontal extent along that
/// direction over its extent across it. Well above 1 for a person seen side-on.
double DepthOverWidth(const Eigen::AlignedBox3d& subject, const Eigen::Vector3d& direction,
                      UpAxis up);

/// Places `options.views` cameras aiming at the centre of `subject` (the bounding box of every
/// simulated frame), each as far as needed for the whole box to project inside its image.
/// Fails on an empty box, fewer than one view, a bad image size or field of view.
StatusOr<std::vector<ViewCalibration>> PlaceCameras(const Eigen::AlignedBox3d& subject,
                                                    const RigOptions& options);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_SIM_RIG_H_
