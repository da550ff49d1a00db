// Simulated colour: the albedo fixed to the surface, its sampling by the ray caster, each
// view's exposure and noise, and the coloured ground truth written beside the capture.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include <nlohmann/json.hpp>

#include "codec/common/triangle_distance.h"
#include "tests/test_util.h"
#include "tools/io/capture.h"
#include "tools/io/mesh_io.h"
#include "tools/io/mesh_sequence.h"
#include "tools/sim/albedo.h"
#include "tools/sim/range_sensor.h"
#include "tools/sim/raycaster.h"
#include "tools/sim/rig.h"
#include "tools/sim/scenes.h"
#include "tools/sim/simulator.h"

namespace meshvid {
namespace {

/// A 160x120 camera at the origin looking along +z (world = camera frame).
ViewCalibration OriginCamera() {
  RigOptions rig;
  rig.width = 160;
  rig.height = 120;
  ViewCalibration view;
  view.intrinsics = RigIntrinsics(rig);
  view.has_extrinsics = true;
  return view;
}

/// A plane at z = 2 whose red channel grows linearly with x (0 at x = -0.5, 200 at
/// x = 0.5), green with y, blue constant.
TriangleMesh GradientPlane() {
  TriangleMesh plane = testing::MakeGridPlane(1.0f, 4, 2.0f);
  for (const Eigen::Vector3f& p : plane.positions) {
    plane.colours.push_back(Colour(static_cast<std::uint8_t>(std::lround(200 * (p.x() + 0.5))),
                                   static_cast<std::uint8_t>(std::lround(200 * (p.y() + 0.5))),
                                   90));
  }
  return plane;
}

RayCastImage CastOnce(const TriangleMesh& mesh, const ViewCalibration& view) {
  auto caster = RayCaster::Create();
  EXPECT_TRUE(caster.ok());
  EXPECT_TRUE((*caster)->SetMesh(mesh).ok());
  RayCastImage image;
  EXPECT_TRUE((*caster)->Cast(view, &image).ok());
  return image;
}

TEST(AlbedoTest, IsAFunctionOfPositionWithGradientsAndEdges) {
  auto scene = MakeArmBlockScene();
  auto rest = scene->Frame(0);
  ASSERT_TRUE(rest.ok());
  const std::vector<Colour> albedo = PaintAlbedo(*rest);
  ASSERT_EQ(albedo.size(), rest->vertex_count());
  EXPECT_EQ(PaintAlbedo(*rest), albedo);  // deterministic
  std::set<std::uint32_t> distinct;
  for (const Colour& c : albedo) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(c[k], 24);
      EXPECT_LE(c[k], 224);
    }
    distinct.insert(c[0] << 16 | c[1] << 8 | c[2]);
  }
  EXPECT_GT(distinct.size(), albedo.size() / 10);  // not a flat colour
  EXPECT_TRUE(PaintAlbedo(TriangleMesh()).empty());
}

TEST(RayCasterColourTest, HitsBlendTheTrianglesVertexColours) {
  const ViewCalibration view = OriginCamera();
  const RayCastImage image = CastOnce(GradientPlane(), view);
  ASSERT_EQ(image.colour.size(), image.depth.size());
  const PinholeIntrinsics& k = *view.intrinsics;
  long checked = 0;
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      const std::size_t pixel = static_cast<std::size_t>(v) * k.width + u;
      if (!(image.depth[pixel] > 0)) continue;
      const Eigen::Vector3d hit = k.RayThrough(u, v) * image.depth[pixel];
      // The vertex colours are rounded to 8 bits, so the blend is within half a unit.
      EXPECT_NEAR(image.colour[pixel].x(), 200 * (hit.x() + 0.5), 0.51);
      EXPECT_NEAR(image.colour[pixel].y(), 200 * (hit.y() + 0.5), 0.51);
      EXPECT_FLOAT_EQ(image.colour[pixel].z(), 90.0f);
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
  // A mesh without colours gives no colour image.
  TriangleMesh grey = GradientPlane();
  grey.colours.clear();
  EXPECT_TRUE(CastOnce(grey, view).colour.empty());
}

TEST(SensorColourTest, ExposureScalesNoiseAddsAndDepthIsUntouched) {
  const ViewCalibration view = OriginCamera();
  TriangleMesh flat = testing::MakeGridPlane(1.0f, 4, 2.0f);
  flat.colours.assign(flat.vertex_count(), Colour(100, 150, 50));
  const RayCastImage image = CastOnce(flat, view);

  SensorOptions exact;
  exact.exposure_spread = 0;
  exact.colour_noise = 0;
  const RangeScan plain = ApplySensorModel(image, view, exact, 0, 0);
  ASSERT_EQ(plain.grid.colours.size(), plain.grid.depth.size());
  for (std::size_t i = 0; i < plain.grid.depth.size(); ++i) {
    if (plain.grid.depth[i] > 0) {
      EXPECT_EQ(plain.grid.colours[i], Colour(100, 150, 50));
    }
  }

  // Exposure: one gain per view, the same at every frame, different between views.
  SensorOptions exposed = exact;
  exposed.exposure_spread = 0.2;
  EXPECT_NE(ViewExposureGain(exposed, 0), ViewExposureGain(exposed, 1));
  EXPECT_EQ(ViewExposureGain(exact, 3), 1.0);
  for (int view_index : {0, 1}) {
    const double gain = ViewExposureGain(exposed, view_index);
    for (int frame : {0, 7}) {
      const RangeScan scan = ApplySensorModel(image, view, exposed, frame, view_index);
      for (std::size_t i = 0; i < scan.grid.depth.size(); i += 7) {
        if (!(scan.grid.depth[i] > 0)) continue;
        EXPECT_EQ(scan.grid.colours[i][0], std::clamp(std::lround(100 * gain), 0L, 255L));
        EXPECT_EQ(scan.grid.colours[i][1], std::clamp(std::lround(150 * gain), 0L, 255L));
      }
    }
  }

  // Noise: zero mean, the given sigma, per channel and sample.
  SensorOptions noisy = exact;
  noisy.colour_noise = 4.0;
  const RangeScan scan = ApplySensorModel(image, view, noisy, 0, 0);
  double sum = 0, sum_squares = 0;
  long count = 0;
  for (std::size_t i = 0; i < scan.grid.depth.size(); ++i) {
    if (!(scan.grid.depth[i] > 0)) continue;
    const double error = scan.grid.colours[i][1] - 150.0;
    sum += error;
    sum_squares += error * error;
    ++count;
  }
  ASSERT_GT(count, 1000);
  EXPECT_NEAR(sum / count, 0.0, 0.3);
  EXPECT_NEAR(std::sqrt(sum_squares / count), 4.0, 0.3);

  // The depth samples are the same with and without colour.
  RayCastImage colourless = image;
  colourless.colour.clear();
  SensorOptions depth_noise;
  const RangeScan with = ApplySensorModel(image, view, depth_noise, 2, 1);
  const RangeScan without = ApplySensorModel(colourless, view, depth_noise, 2, 1);
  EXPECT_EQ(with.grid.depth, without.grid.depth);
  EXPECT_TRUE(without.grid.colours.empty());
}

TEST(SensorColourTest, OptionsAreChecked) {
  SensorOptions options;
  options.exposure_spread = -0.1;
  EXPECT_EQ(ValidateSensorOptions(options).code(), StatusCode::kInvalidArgument);
  options = SensorOptions();
  options.exposure_spread = std::nan("");
  EXPECT_EQ(ValidateSensorOptions(options).code(), StatusCode::kInvalidArgument);
  options = SensorOptions();
  options.colour_noise = -1;
  EXPECT_EQ(ValidateSensorOptions(options).code(), StatusCode::kInvalidArgument);
  options.colour_noise = 300;
  EXPECT_EQ(ValidateSensorOptions(options).code(), StatusCode::kInvalidArgument);
}

SimulateOptions SmallOptions() {
  SimulateOptions options;
  options.rig.width = 120;
  options.rig.height = 90;
  options.first_frame = 4;
  options.end_frame = 7;
  options.ground_truth_spec = "scene:arm-block";
  return options;
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(SimulatedColourTest, AlbedoRidesTheSurfaceAndIsWrittenWithTheGroundTruth) {
  testing::TempDir dir;
  const std::string out = dir.File("capture");
  auto scene = MakeArmBlockScene();
  auto summary = SimulateCapture(*scene, out, SmallOptions());
  ASSERT_TRUE(summary.ok()) << summary.status().ToString();
  EXPECT_EQ(summary->colour_source, ColourSource::kAlbedo);
  ASSERT_EQ(summary->exposure_gains.size(), 3u);
  const nlohmann::json simulate = ReadJson(out + "/simulate.json");
  EXPECT_EQ(simulate["colour"]["source"], "albedo");
  EXPECT_EQ(simulate["colour"]["exposure_gains"].size(), 3u);

  // The ground truth's colour is source frame 0's albedo at every frame.
  auto rest = scene->Frame(0);
  ASSERT_TRUE(rest.ok());
  const std::vector<Colour> albedo = PaintAlbedo(*rest);
  auto truth = OpenMeshSequence(out + "/ground_truth.obj");
  ASSERT_TRUE(truth.ok()) << truth.status().ToString();
  for (int t = 0; t < 3; ++t) {
    auto frame = (*truth)->Frame(t);
    ASSERT_TRUE(frame.ok());
    EXPECT_EQ(frame->colours, albedo) << "frame " << t;
  }

  // Every view vertex has a colour, each channel within the view's gain of the albedo's range
  // plus a few sigma of noise.
  auto capture = CaptureSequence::Open(summary->manifest_path);
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  for (int v = 0; v < 3; ++v) {
    auto view = (*capture)->LoadView(1, v);
    ASSERT_TRUE(view.ok()) << view.status().ToString();
    ASSERT_EQ(view->colours.size(), view->vertex_count());
    const double gain = summary->exposure_gains[v];
    for (const Colour& c : view->colours) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(c[k], std::floor(24 * gain - 12));
        EXPECT_LE(c[k], std::min(255.0, std::ceil(224 * gain + 12)));
      }
    }
  }
}

/// The colour of `mesh` (vertex colours `colours`) at its surface point nearest `p`: the
/// nearest triangle's vertex colours blended at that point (brute force).
Eigen::Vector3f ColourNearest(const TriangleMesh& mesh, const std::vector<Colour>& colours,
                              const Eigen::Vector3f& p) {
  float best = std::numeric_limits<float>::infinity();
  Eigen::Vector3f colour = Eigen::Vector3f::Zero();
  for (const Triangle& t : mesh.triangles) {
    const Eigen::Vector3f &a = mesh.positions[t[0]], &b = mesh.positions[t[1]],
                          &c = mesh.positions[t[2]];
    const Eigen::Vector3f q = ClosestPointOnTriangle(p, a, b, c);
    const float distance = (q - p).squaredNorm();
    if (!(distance < best)) continue;
    best = distance;
    // Barycentric weights of q.
    const Eigen::Vector3f e0 = b - a, e1 = c - a, e2 = q - a;
    const float d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
    const float d20 = e2.dot(e0), d21 = e2.dot(e1);
    const float denominator = d00 * d11 - d01 * d01;
    if (!(denominator > 0)) continue;
    const float wb = (d11 * d20 - d01 * d21) / denominator;
    const float wc = (d00 * d21 - d01 * d20) / denominator;
    colour = (1 - wb - wc) * colours[t[0]].cast<float>() + wb * colours[t[1]].cast<float>() +
             wc * colours[t[2]].cast<float>();
  }
  return colour;
}

TEST(SimulatedColourTest, EachViewSeesTheColourOfTheSurfaceWhereItLooks) {
  testing::TempDir dir;
  const std::string out = dir.File("capture");
  auto scene = MakeArmBlockScene();
  SimulateOptions options = SmallOptions();
  options.sensor.exposure_spread = 0;
  options.sensor.colour_noise = 0;
  options.sensor.noise_sigma = 0;
  auto summary = SimulateCapture(*scene, out, options);
  ASSERT_TRUE(summary.ok()) << summary.status().ToString();
  // Source frame 6 (capture frame 2): the arm has moved from its rest pose, and the colour
  // went with it. Each sample's colour is the ground truth's at the surface point it shows;
  // the rest pose's colour at the same place in space is another.
  auto posed = scene->Frame(6);
  auto rest = scene->Frame(0);
  ASSERT_TRUE(posed.ok() && rest.ok());
  const std::vector<Colour> albedo = PaintAlbedo(*rest);
  auto view = ReadMesh(out + "/" + SimulatedViewFileName(2, 1));
  ASSERT_TRUE(view.ok()) << view.status().ToString();
  ASSERT_EQ(view->colours.size(), view->vertex_count());
  double on_surface = 0, in_space = 0;
  int count = 0;
  for (std::size_t i = 0; i < view->vertex_count(); i += 41) {
    const Eigen::Vector3f& p = view->positions[i];
    const Eigen::Vector3f seen = view->colours[i].cast<float>();
    on_surface += (seen - ColourNearest(*posed, albedo, p)).cwiseAbs().sum();
    in_space += (seen - ColourNearest(*rest, albedo, p)).cwiseAbs().sum();
    ++count;
  }
  ASSERT_GT(count, 25);
  on_surface /= 3.0 * count;
  in_space /= 3.0 * count;
  EXPECT_LT(on_surface, 1.0);  // 8-bit rounding, and the shot's position rounded to float
  EXPECT_GT(in_space, 10.0);
  std::printf("mean colour difference: %.2f to the surface, %.2f to the rest pose\n", on_surface,
              in_space);
}

TEST(SimulatedColourTest, OffGivesNoColourAnywhere) {
  testing::TempDir dir;
  const std::string out = dir.File("capture");
  auto scene = MakeArmBlockScene();
  SimulateOptions options = SmallOptions();
  options.colour = false;
  auto summary = SimulateCapture(*scene, out, options);
  ASSERT_TRUE(summary.ok()) << summary.status().ToString();
  EXPECT_EQ(summary->colour_source, ColourSource::kNone);
  EXPECT_TRUE(summary->exposure_gains.empty());
  auto view = ReadMesh(out + "/" + SimulatedViewFileName(0, 0));
  ASSERT_TRUE(view.ok());
  EXPECT_TRUE(view->colours.empty());
  auto truth = ReadMesh(out + "/ground_truth.obj");
  ASSERT_TRUE(truth.ok());
  EXPECT_TRUE(truth->colours.empty());
  EXPECT_EQ(ReadJson(out + "/simulate.json")["colour"]["source"], "none");
}

/// Writes two frames of a plane facing the default rig (z = 0, y up) into `folder`, with
/// vertex colours if `coloured`.
void WritePlaneFrames(const std::string& folder, bool coloured) {
  std::filesystem::create_directories(folder);
  for (int f = 0; f < 2; ++f) {
    TriangleMesh plane = testing::MakeGridPlane(1.0f, 6 + f, 0.0f);  // a new grid each frame
    if (coloured) plane.colours.assign(plane.vertex_count(), Colour(200, 40, 10 + f));
    ASSERT_TRUE(WriteMesh(folder + "/f" + std::to_string(f) + ".obj", plane).ok());
  }
}

TEST(SimulatedColourTest, GroundTruthColoursAreUsedAndChangingMeshesWithoutThemGetNone) {
  testing::TempDir dir;
  SimulateOptions options;
  options.rig.width = 80;
  options.rig.height = 60;
  options.sensor.exposure_spread = 0;
  options.sensor.colour_noise = 0;

  WritePlaneFrames(dir.File("coloured"), true);
  auto coloured = OpenMeshSequence(dir.File("coloured"));
  ASSERT_TRUE(coloured.ok()) << coloured.status().ToString();
  ASSERT_FALSE((*coloured)->fixed_connectivity());
  auto summary = SimulateCapture(**coloured, dir.File("out1"), options);
  ASSERT_TRUE(summary.ok()) << summary.status().ToString();
  EXPECT_EQ(summary->colour_source, ColourSource::kGroundTruth);
  for (int f = 0; f < 2; ++f) {
    auto view = ReadMesh(dir.File("out1") + "/" + SimulatedViewFileName(f, 1));
    ASSERT_TRUE(view.ok());
    ASSERT_FALSE(view->colours.empty());
    for (const Colour& c : view->colours) EXPECT_EQ(c, Colour(200, 40, 10 + f));
    auto truth = ReadMesh(dir.File("out1") + "/ground_truth/f000" + std::to_string(f) + ".obj");
    ASSERT_TRUE(truth.ok());
    EXPECT_FALSE(truth->colours.empty());
  }

  WritePlaneFrames(dir.File("grey"), false);
  auto grey = OpenMeshSequence(dir.File("grey"));
  ASSERT_TRUE(grey.ok());
  summary = SimulateCapture(**grey, dir.File("out2"), options);
  ASSERT_TRUE(summary.ok()) << summary.status().ToString();
  EXPECT_EQ(summary->colour_source, ColourSource::kNone);
  auto view = ReadMesh(dir.File("out2") + "/" + SimulatedViewFileName(0, 0));
  ASSERT_TRUE(view.ok());
  EXPECT_TRUE(view->colours.empty());
}

}  // namespace
}  // namespace meshvid
