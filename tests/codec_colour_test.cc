// Surface colour in the encoder: the views' colours at the displacement shots, their exposure
// put level, and fused without seams where the views' coverage changes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "codec/common/colour_space.h"
#include "codec/common/subdivision.h"
#include "codec/enc/key_groups/colour.h"
#include "codec/enc/key_groups/detail.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

using testing::MakeGridPlane;

/// The colour painted on the test plane at (x, y): a gradient in every channel.
Eigen::Vector3f Albedo(const Eigen::Vector3f& p) {
  return Eigen::Vector3f(80 + 100 * (p.x() + 0.5f), 120 + 60 * p.y(), 60 + 40 * p.x() * p.y());
}

/// A range view of the plane z = 0.002 over x in [x_min, x_max] (y in [-0.6, 0.6]), its colours the
/// albedo times `gain`, rounded to 8 bits as a camera stores them.
TriangleMesh StripView(float x_min, float x_max, double gain) {
  TriangleMesh grid = MakeGridPlane(1.2f, 60, 0.002f);  // past the base's edges
  std::vector<Triangle> kept;
  for (const Triangle& t : grid.triangles) {
    bool inside = true;
    for (int c = 0; c < 3; ++c) {
      const float x = grid.positions[t[c]].x();
      inside = inside && x >= x_min - 1e-6f && x <= x_max + 1e-6f;
    }
    if (inside) kept.push_back(t);
  }
  grid.triangles = kept;
  grid.normals.clear();
  for (const Eigen::Vector3f& p : grid.positions) {
    const Eigen::Vector3f c = (gain * Albedo(p).cast<double>()).cast<float>();
    grid.colours.push_back(c.array().round().cwiseMax(0).cwiseMin(255).cast<std::uint8_t>());
  }
  RemoveUnreferencedVertices(&grid);
  return grid;
}

ViewCalibration CameraAt(const Eigen::Vector3d& position) {
  ViewCalibration camera;
  camera.world_from_camera.translation() = position;
  camera.has_extrinsics = true;
  return camera;
}

struct Scene {
  TriangleMesh base = MakeGridPlane(1.0f, 8, 0.0f);
  RegularSubdivision lattice = RegularSubdivision::Create(base, 2).value();
  std::vector<TriangleMesh> views;
  std::vector<ViewCalibration> cameras;
  std::vector<Eigen::Vector3f> sample_points;

  explicit Scene(const std::vector<double>& gains) {
    // Left, right and middle strips: the coverage changes at x = -0.3, -0.15, 0.15 and 0.3.
    views = {StripView(-0.6f, 0.15f, gains[0]), StripView(-0.15f, 0.6f, gains[1]),
             StripView(-0.3f, 0.3f, gains[2])};
    cameras = {CameraAt({-1, 0, 2}), CameraAt({1, 0, 2}), CameraAt({0, 0, 2})};
    std::vector<Eigen::Vector3f> normals, directions;
    ComputeVertexNormals(base.positions, base.triangles, &normals);
    EvaluateSampleFrames(lattice, lattice.levels(), base.positions, normals, &sample_points,
                         &directions);
  }

  ColourObservations Observe(std::vector<float>* displacements) const {
    DetailOptions options;
    options.shot = {0.1f, 0.5f};
    options.outlier_distance = 0.005f;
    ColourObservations observations;
    auto hits = MeasureDisplacements(lattice, base.positions, views, options, displacements,
                                     cameras, &observations);
    EXPECT_TRUE(hits.ok()) << hits.status().ToString();
    if (hits.ok()) {
      EXPECT_EQ(*hits, lattice.samples().size());
    }
    return observations;
  }

  /// The largest difference between the fused colour and the albedo times the best single
  /// factor (the fused colour's exposure is the views' geometric mean, not the albedo's).
  double WorstSeam(const std::array<std::vector<float>, 3>& fused) const {
    double ratio_sum = 0;
    for (std::size_t s = 0; s < sample_points.size(); ++s) {
      ratio_sum += fused[0][s] / Albedo(sample_points[s]).x();
    }
    const double factor = ratio_sum / sample_points.size();
    double worst = 0;
    for (std::size_t s = 0; s < sample_points.size(); ++s) {
      const Eigen::Vector3f truth = Albedo(sample_points[s]);
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(fused[c][s] - factor * truth[c]));
      }
    }
    return worst;
  }
};

TEST(Colour, ViewsWithOtherExposuresFuseWithoutSeams) {
  const std::vector<double> true_gains = {0.85, 1.0, 1.2};
  const Scene scene(true_gains);
  std::vector<float> displacements;
  const ColourObservations observations = scene.Observe(&displacements);
  for (float d : displacements) EXPECT_NEAR(d, 0.002f, 1e-5f);

  const std::vector<double> gains = EstimateExposureGains(observations);
  ASSERT_EQ(gains.size(), 3u);
  EXPECT_NEAR(gains[0] / gains[2], true_gains[0] / true_gains[2], 0.01);
  EXPECT_NEAR(gains[1] / gains[2], true_gains[1] / true_gains[2], 0.01);
  EXPECT_NEAR(std::log(gains[0]) + std::log(gains[1]) + std::log(gains[2]), 0.0, 1e-9);

  std::array<std::vector<float>, 3> fused;
  FuseColours(observations, gains, &fused);
  EXPECT_LE(scene.WorstSeam(fused), 3.0);

  // Fused at face value, the exposures show as seams where the coverage changes.
  FuseColours(observations, std::vector<double>(3, 1.0), &fused);
  EXPECT_GT(scene.WorstSeam(fused), 10.0);
}

TEST(Colour, WeightsFollowTheAngleAtWhichEachCameraSeesTheSurface) {
  const Scene scene({1.0, 1.0, 1.0});
  std::vector<float> displacements;
  const ColourObservations observations = scene.Observe(&displacements);
  ASSERT_EQ(observations.weight.size(), 3u);
  for (std::size_t s = 0; s < scene.sample_points.size(); ++s) {
    const Eigen::Vector3f hit = scene.sample_points[s] + Eigen::Vector3f(0, 0, 0.002f);
    for (std::size_t v = 0; v < 3; ++v) {
      const float w = observations.weight[v][s];
      if (w == 0) continue;
      const Eigen::Vector3f ray =
          hit - scene.cameras[v].world_from_camera.translation().cast<float>();
      const float cos = std::abs(ray.z()) / ray.norm();
      EXPECT_NEAR(w, cos * cos, 1e-4f) << "view " << v << " sample " << s;
      EXPECT_NEAR(observations.colour[v][s].x(), Albedo(scene.sample_points[s]).x(), 0.6f);
    }
  }
  // Seen from straight above the middle view weighs 1 at the centre; the side cameras less.
  std::size_t centre = 0;
  for (std::size_t s = 0; s < scene.sample_points.size(); ++s) {
    if (scene.sample_points[s].norm() < scene.sample_points[centre].norm()) centre = s;
  }
  EXPECT_NEAR(observations.weight[2][centre], 1.0f, 1e-4f);
  EXPECT_LT(observations.weight[0][centre], 0.85f);
}

TEST(Colour, ViewsWithoutColourAddNothingAndDisplacementsStayTheSame) {
  Scene scene({1.0, 1.0, 1.0});
  scene.views[1].colours.clear();
  std::vector<float> with_colour, without_colour;
  const ColourObservations observations = scene.Observe(&with_colour);
  for (float w : observations.weight[1]) EXPECT_EQ(w, 0.0f);
  DetailOptions options;
  options.shot = {0.1f, 0.5f};
  options.outlier_distance = 0.005f;
  ASSERT_TRUE(MeasureDisplacements(scene.lattice, scene.base.positions, scene.views, options,
                                   &without_colour)
                  .ok());
  ASSERT_EQ(with_colour.size(), without_colour.size());
  for (std::size_t s = 0; s < with_colour.size(); ++s) {
    EXPECT_EQ(with_colour[s], without_colour[s]) << "sample " << s;
  }
  // One view overlapping none: gain 1; no views: nothing fused.
  ColourObservations lone;
  lone.Reset(1, 4);
  EXPECT_EQ(EstimateExposureGains(lone), std::vector<double>{1.0});
  std::array<std::vector<float>, 3> fused;
  FuseColours(lone, EstimateExposureGains(lone), &fused);
  for (const auto& channel : fused) {
    ASSERT_EQ(channel.size(), 4u);
    for (float c : channel) EXPECT_TRUE(std::isnan(c));
  }
}

TEST(Colour, AnOutlierViewGivesNoColour) {
  Scene scene({1.0, 1.0, 1.0});
  std::vector<float> displacements;
  const ColourObservations before = scene.Observe(&displacements);
  // The right view floats 3 cm off the surface: its hits are outliers for the displacement
  // (the two other views agree), and its colour must not count either.
  for (Eigen::Vector3f& p : scene.views[1].positions) p.z() += 0.03f;
  const ColourObservations after = scene.Observe(&displacements);
  std::size_t outvoted = 0;
  for (std::size_t s = 0; s < scene.sample_points.size(); ++s) {
    const bool all_three_saw =
        before.weight[0][s] > 0 && before.weight[1][s] > 0 && before.weight[2][s] > 0;
    if (!all_three_saw) continue;
    EXPECT_EQ(after.weight[1][s], 0.0f) << "sample " << s;
    EXPECT_GT(after.weight[0][s], 0.0f) << "sample " << s;
    ++outvoted;
  }
  EXPECT_GT(outvoted, 10u);
}

TEST(Colour, FilledColoursComeFromTheSeenSamplesAndGreyWhereNoneWasEverSeen) {
  const Scene scene({1.0, 1.0, 1.0});
  const SampleGraph graph = SampleGraph::Build(scene.lattice);
  const std::size_t n = scene.lattice.samples().size();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::array<std::vector<float>, 3> last_seen;

  // A run of one frame no view saw: neutral grey everywhere.
  std::array<std::vector<std::vector<float>>, 3> unseen;
  for (auto& channel : unseen) channel.assign(1, std::vector<float>(n, nan));
  const auto grey = FillColours(graph, &unseen, &last_seen);
  ASSERT_EQ(grey.size(), 1u);
  ASSERT_EQ(grey[0].size(), n);
  for (const Colour& c : grey[0]) EXPECT_EQ(c, Colour(128, 128, 128));

  // The next run: frame 0 sees the left half in one colour, frame 1 sees all in another.
  const Eigen::Vector3f left(200, 100, 50), all(10, 20, 30);
  std::array<std::vector<std::vector<float>>, 3> run;
  for (int c = 0; c < 3; ++c) {
    run[c].assign(2, std::vector<float>(n, nan));
    for (std::size_t s = 0; s < n; ++s) {
      if (scene.sample_points[s].x() < 0) run[c][0][s] = left[c];
      run[c][1][s] = all[c];
    }
  }
  const auto colours = FillColours(graph, &run, &last_seen);
  ASSERT_EQ(colours.size(), 2u);
  int unseen_checked = 0;
  for (std::size_t s = 0; s < n; ++s) {
    EXPECT_EQ(colours[1][s], RoundTo8Bits(all)) << s;
    if (scene.sample_points[s].x() < 0) {
      EXPECT_EQ(colours[0][s], RoundTo8Bits(left)) << s;
    } else {
      // Unseen in frame 0: between what its neighbours saw then and what it saw next.
      for (int c = 0; c < 3; ++c) {
        EXPECT_GE(colours[0][s][c], std::min(left[c], all[c])) << s;
        EXPECT_LE(colours[0][s][c], std::max(left[c], all[c])) << s;
      }
      ++unseen_checked;
    }
  }
  EXPECT_GT(unseen_checked, 10);
  // The latest colours carry on to the next run.
  for (int c = 0; c < 3; ++c) {
    ASSERT_EQ(last_seen[c].size(), n);
    EXPECT_FLOAT_EQ(last_seen[c][0], all[c]);
  }
}

}  // namespace
}  // namespace meshvid
