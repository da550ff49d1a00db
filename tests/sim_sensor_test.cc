// The simulated range sensor: exact depths, noise statistics, grazing rejection, drop-outs,
// determinism.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

#include "tests/test_util.h"
#include "tools/sim/range_sensor.h"
#include "tools/sim/raycaster.h"
#include "tools/sim/rig.h"
#include "tools/sim/scenes.h"

namespace meshvid {
namespace {

/// A 320x240 camera at the origin looking along +z (world = camera frame).
ViewCalibration OriginCamera() {
  RigOptions rig;
  rig.width = 320;
  rig.height = 240;
  ViewCalibration view;
  view.intrinsics = RigIntrinsics(rig);
  view.has_extrinsics = true;
  return view;
}

RangeScan ScanOnce(const TriangleMesh& mesh, const ViewCalibration& view,
                   const SensorOptions& options) {
  auto simulator = CaptureSimulator::Create({view}, options);
  EXPECT_TRUE(simulator.ok()) << simulator.status().ToString();
  auto scans = (*simulator)->ScanFrame(mesh, 0);
  EXPECT_TRUE(scans.ok()) << scans.status().ToString();
  return std::move(scans->front());
}

TEST(RangeSensorTest, PlaneAtKnownDistanceGivesExactDepths) {
  constexpr float kDistance = 2.0f;
  constexpr float kSide = 1.0f;
  const TriangleMesh plane = testing::MakeGridPlane(kSide, 4, kDistance);
  const ViewCalibration view = OriginCamera();
  SensorOptions options;
  options.noise_sigma = 0;
  const RangeScan scan = ScanOnce(plane, view, options);

  const PinholeIntrinsics& k = *view.intrinsics;
  long expected_hits = 0;
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      const Eigen::Vector3d ray = k.RayThrough(u, v) * kDistance;
      const bool meets = std::abs(ray.x()) < kSide / 2 && std::abs(ray.y()) < kSide / 2;
      expected_hits += meets;
      const float depth = scan.grid.depth[static_cast<std::size_t>(v) * k.width + u];
      if (meets) {
        EXPECT_NEAR(depth, kDistance, 1e-4 * kDistance) << "pixel " << u << "," << v;
      } else {
        EXPECT_EQ(depth, 0.0f) << "pixel " << u << "," << v;
      }
    }
  }
  EXPECT_EQ(expected_hits, 132 * 132);
  EXPECT_EQ(scan.hit_pixels, expected_hits);
  EXPECT_EQ(scan.valid_samples, expected_hits);
}

TEST(RangeSensorTest, NoiseAlongTheRayHasZeroMeanAndSigma) {
  constexpr double kDistance = 2.0;
  constexpr double kSigma = 0.01;
  const TriangleMesh plane = testing::MakeGridPlane(20.0f, 4, kDistance);
  const ViewCalibration view = OriginCamera();
  SensorOptions options;
  options.noise_sigma = kSigma;
  const RangeScan scan = ScanOnce(plane, view, options);
  const PinholeIntrinsics& k = *view.intrinsics;
  double sum = 0, sum_squares = 0;
  long count = 0;
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      const std::size_t pixel = static_cast<std::size_t>(v) * k.width + u;
      ASSERT_GT(scan.grid.depth[pixel], 0.0f);
      const double true_range = kDistance * k.RayThrough(u, v).norm();
      const double error = scan.grid.points[pixel].cast<double>().norm() - true_range;
      sum += error;
      sum_squares += error * error;
      ++count;
    }
  }
  ASSERT_GE(count, 50000);
  const double mean = sum / count;
  const double std_dev = std::sqrt(sum_squares / count - mean * mean);
  EXPECT_LT(std::abs(mean), 4 * kSigma / std::sqrt(static_cast<double>(count)));
  EXPECT_NEAR(std_dev, kSigma, 0.05 * kSigma);
}

TEST(RangeSensorTest, GrazingSamplesAreRejected) {
  // A large plane through (0, 0, 2) whose normal is turned 60 degrees about y: the angle
  // between ray and normal runs from about 29 to 91 degrees across the image.
  TriangleMesh plane = testing::MakeGridPlane(200.0f, 8, 0.0f);
  const Eigen::Vector3d normal =
      Eigen::AngleAxisd(60 * std::numbers::pi / 180, Eigen::Vector3d::UnitY()) *
      Eigen::Vector3d::UnitZ();
  TransformMesh(Eigen::Translation3d(0, 0, 2) *
                    Eigen::AngleAxisd(60 * std::numbers::pi / 180, Eigen::Vector3d::UnitY()),
                &plane);
  const ViewCalibration view = OriginCamera();
  SensorOptions options;
  options.noise_sigma = 0;
  options.max_angle_deg = 75;
  const RangeScan scan = ScanOnce(plane, view, options);
  const PinholeIntrinsics& k = *view.intrinsics;
  long kept = 0, rejected = 0;
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      const double angle = std::acos(std::abs(k.RayThrough(u, v).normalized().dot(normal))) *
                           180 / std::numbers::pi;
      const std::size_t pixel = static_cast<std::size_t>(v) * k.width + u;
      if (std::abs(angle - 75) < 0.05 || angle > 89) continue;  // ties and near-parallel rays
      const bool valid = scan.grid.depth[pixel] > 0;
      EXPECT_EQ(valid, angle <= 75) << "pixel " << u << "," << v << " angle " << angle;
      (valid ? kept : rejected)++;
    }
  }
  EXPECT_GT(kept, 10000);
  EXPECT_GT(rejected, 10000);
}

TEST(RangeSensorTest, DropoutRemovesTheRequestedShare) {
  const TriangleMesh plane = testing::MakeGridPlane(20.0f, 4, 2.0f);
  SensorOptions options;
  options.noise_sigma = 0;
  options.dropout = 0.3;
  const RangeScan scan = ScanOnce(plane, OriginCamera(), options);
  ASSERT_EQ(scan.hit_pixels, 320 * 240);
  const double kept_share = static_cast<double>(scan.valid_samples) / scan.hit_pixels;
  EXPECT_NEAR(kept_share, 0.7, 0.01);
}

TEST(RangeSensorTest, InvalidOptionsAreRefused) {
  SensorOptions options;
  options.dropout = 1.0;
  EXPECT_EQ(ValidateSensorOptions(options).code(), StatusCode::kInvalidArgument);
  options.dropout = -0.1;
  EXPECT_EQ(ValidateSensorOptions(options).code(), StatusCode::kInvalidArgument);
  options = SensorOptions();
  options.noise_sigma = -1;
  EXPECT_EQ(ValidateSensorOptions(options).code(), StatusCode::kInvalidArgument);
  options = SensorOptions();
  options.max_angle_deg = 0;
  EXPECT_EQ(ValidateSensorOptions(options).code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(CaptureSimulator::Create({}, SensorOptions()).ok());
}

/// Simulates frame 3 of the cloth with three 160x120 views.
std::vector<TriangleMesh> SimulateCloth(std::uint64_t seed) {
  auto scene = MakeClothScene();
  auto mesh = scene->Frame(3);
  EXPECT_TRUE(mesh.ok());
  RigOptions rig;
  rig.width = 160;
  rig.height = 120;
  const Eigen::AlignedBox3f box = BoundingBox(*mesh);
  auto views = PlaceCameras(box.cast<double>(), rig);
  EXPECT_TRUE(views.ok());
  SensorOptions options;
  options.seed = seed;
  options.dropout = 0.1;
  auto simulator = CaptureSimulator::Create(*views, options);
  EXPECT_TRUE(simulator.ok());
  auto meshes = (*simulator)->SimulateFrame(*mesh, 3);
  EXPECT_TRUE(meshes.ok());
  return *meshes;
}

bool SameMeshes(const std::vector<TriangleMesh>& a, const std::vector<TriangleMesh>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].positions != b[i].positions || a[i].triangles != b[i].triangles) return false;
  }
  return true;
}

TEST(RangeSensorTest, SameSeedSameMeshesWhateverTheThreadCount) {
  const std::vector<TriangleMesh> first = SimulateCloth(7);
  ASSERT_EQ(first.size(), 3u);
  for (const TriangleMesh& mesh : first) EXPECT_GT(mesh.triangle_count(), 1000u);
  std::vector<TriangleMesh> single_thread;
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    single_thread = SimulateCloth(7);
  }
  EXPECT_TRUE(SameMeshes(first, single_thread));
  EXPECT_TRUE(SameMeshes(first, SimulateCloth(7)));
  EXPECT_FALSE(SameMeshes(first, SimulateCloth(8)));
}

}  // namespace
}  // namespace meshvid
