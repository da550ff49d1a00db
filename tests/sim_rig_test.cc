// Camera placement of the simulated rig.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tools/sim/rig.h"

namespace meshvid {
namespace {

const Eigen::AlignedBox3d kSubject(Eigen::Vector3d(-0.4, 0.0, -0.3), Eigen::Vector3d(0.4, 1.8, 0.3));

/// Angle in degrees of a camera's position around +y, from +z towards +x.
double AzimuthOf(const ViewCalibration& view) {
  const Eigen::Vector3d offset = view.world_from_camera.translation() - kSubject.center();
  return std::atan2(offset.x(), offset.z()) * 180 / std::numbers::pi;
}

TEST(RigTest, KinectLikeIntrinsicsScaleWithWidth) {
  RigOptions options;
  PinholeIntrinsics k = RigIntrinsics(options);
  EXPECT_DOUBLE_EQ(k.fx, 525.0);
  EXPECT_DOUBLE_EQ(k.fy, 525.0);
  EXPECT_DOUBLE_EQ(k.cx, 319.5);
  EXPECT_DOUBLE_EQ(k.cy, 239.5);
  options.width = 320;
  options.height = 240;
  EXPECT_DOUBLE_EQ(RigIntrinsics(options).fx, 262.5);
  options.fov_deg = 90;
  EXPECT_NEAR(RigIntrinsics(options).fx, 160.0, 1e-9);
}

TEST(RigTest, DefaultArcFacesTheFrontAndFitsTheSubject) {
  auto views = PlaceCameras(kSubject, RigOptions());
  ASSERT_TRUE(views.ok()) << views.status().ToString();
  ASSERT_EQ(views->size(), 3u);
  const double expected[] = {-40, 0, 40};
  for (int i = 0; i < 3; ++i) {
    const ViewCalibration& view = (*views)[i];
    EXPECT_TRUE(view.has_extrinsics);
    EXPECT_NEAR(AzimuthOf(view), expected[i], 1e-9);
    const Eigen::Isometry3d camera_from_world = view.world_from_camera.inverse();
    // Looks at the centre, y down (world up projects upwards in the image).
    const Eigen::Vector3d centre = camera_from_world * kSubject.center();
    EXPECT_NEAR(centre.x(), 0, 1e-9);
    EXPECT_NEAR(centre.y(), 0, 1e-9);
    EXPECT_GT(centre.z(), 0);
    EXPECT_LT((camera_from_world.linear() * Eigen::Vector3d::UnitY()).y(), 0);
    EXPECT_NEAR(view.world_from_camera.linear().determinant(), 1.0, 1e-12);
    // Every corner lands inside the image; the tightest one near the 5% margin.
    double widest = 0;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d p =
          camera_from_world * kSubject.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
      const Eigen::Vector2d pixel = view.intrinsics->Project(p);
      EXPECT_GE(pixel.x(), 0);
      EXPECT_LE(pixel.x(), 639);
      EXPECT_GE(pixel.y(), 0);
      EXPECT_LE(pixel.y(), 479);
      widest = std::max({widest, std::abs(pixel.x() - 319.5) / 320, std::abs(pixel.y() - 239.5) / 240});
    }
    EXPECT_NEAR(widest, 0.95, 1e-6);
  }
}

TEST(RigTest, RingSpreadsViewsAndAzimuthTurnsTheRig) {
  RigOptions options;
  options.views = 4;
  options.layout = RigLayout::kRing;
  options.azimuth_deg = 90;
  auto views = PlaceCameras(kSubject, options);
  ASSERT_TRUE(views.ok());
  const double expected[] = {90, 180, -90, 0};
  for (int i = 0; i < 4; ++i) {
    double difference = std::remainder(AzimuthOf((*views)[i]) - expected[i], 360.0);
    EXPECT_NEAR(difference, 0, 1e-9) << "view " << i;
  }
}

TEST(RigTest, BadRigsAreRefused) {
  RigOptions options;
  options.views = 0;
  EXPECT_EQ(PlaceCameras(kSubject, options).status().code(), StatusCode::kInvalidArgument);
  options = RigOptions();
  options.width = 1;
  EXPECT_EQ(PlaceCameras(kSubject, options).status().code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(PlaceCameras(Eigen::AlignedBox3d(), RigOptions()).ok());
}

}  // namespace
}  // namespace meshvid
