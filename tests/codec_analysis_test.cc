// The encoder's analysis stages: normal shooting, displacement measurement and hole filling.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "codec/enc/key_groups/detail.h"
#include "codec/enc/tracking/normal_shooting.h"
#include "tests/analytic_mvid.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

using testing::MakeGridPlane;

TEST(NormalShooting, FindsTheNearestHitInEitherDirection) {
  const TriangleMesh plane = MakeGridPlane(2.0f, 4, 0.1f);
  auto target = ShootingTarget::Create(plane);
  ASSERT_TRUE(target.ok()) << target.status().ToString();
  ShotLimits limits{0.5f, 0.5f};
  EXPECT_NEAR((*target)->Shoot({0.1f, 0.2f, 0}, {0, 0, 1}, limits), 0.1f, 1e-6f);
  EXPECT_NEAR((*target)->Shoot({0.1f, 0.2f, 0}, {0, 0, -1}, limits), -0.1f, 1e-6f);
  EXPECT_NEAR((*target)->Shoot({0.1f, 0.2f, 0.3f}, {0, 0, 1}, limits), -0.2f, 1e-6f);
  // Too far, off the mesh, or too grazing: misses.
  EXPECT_TRUE(std::isnan((*target)->Shoot({0, 0, -0.5f}, {0, 0, 1}, limits)));
  EXPECT_TRUE(std::isnan((*target)->Shoot({3, 0, 0}, {0, 0, 1}, limits)));
  const Eigen::Vector3f grazing = Eigen::Vector3f(1, 0, 0.2f).normalized();
  EXPECT_TRUE(std::isnan((*target)->Shoot({0, 0, 0}, grazing, limits)));
  std::vector<float> all;
  const std::vector<Eigen::Vector3f> origins(100, Eigen::Vector3f(0, 0, 0.05f));
  const std::vector<Eigen::Vector3f> directions(100, Eigen::Vector3f(0, 0, 1));
  (*target)->ShootAll(origins, directions, limits, &all);
  ASSERT_EQ(all.size(), 100u);
  for (float d : all) EXPECT_NEAR(d, 0.05f, 1e-6f);
}

TEST(NormalShooting, RejectsAnEmptyMesh) {
  EXPECT_FALSE(ShootingTarget::Create(TriangleMesh{}).ok());
}

/// A 4x4-quad plane subdivided to level 2: the lattice of the detail tests.
RegularSubdivision PlaneLattice(const TriangleMesh& plane) {
  return RegularSubdivision::Create(plane, 2).value();
}

TEST(Detail, FusesViewsAroundTheirMedian) {
  const TriangleMesh base = MakeGridPlane(1.0f, 4, 0.0f);
  const RegularSubdivision lattice = PlaneLattice(base);
  const std::vector<TriangleMesh> views = {MakeGridPlane(1.2f, 3, 0.02f),
                                           MakeGridPlane(1.2f, 5, 0.021f),
                                           MakeGridPlane(1.2f, 2, 0.05f)};
  DetailOptions options;
  options.shot = {0.1f, 0.5f};
  options.outlier_distance = 0.005f;
  std::vector<float> displacements;
  auto hits = MeasureDisplacements(lattice, base.positions, views, options, &displacements);
  ASSERT_TRUE(hits.ok()) << hits.status().ToString();
  EXPECT_EQ(*hits, lattice.samples().size());
  for (float d : displacements) EXPECT_NEAR(d, 0.0205f, 1e-5f);
  // One view, and a part of the base it does not cover: misses there.
  const std::vector<TriangleMesh> half = {MakeGridPlane(0.5f, 4, -0.01f)};
  hits = MeasureDisplacements(lattice, base.positions, half, options, &displacements);
  ASSERT_TRUE(hits.ok());
  EXPECT_GT(*hits, 0u);
  EXPECT_LT(*hits, lattice.samples().size());
  for (float d : displacements) {
    if (!std::isnan(d)) {
      EXPECT_NEAR(d, -0.01f, 1e-5f);
    }
  }
  // A posed base of the wrong size is refused.
  EXPECT_FALSE(MeasureDisplacements(lattice, std::vector<Eigen::Vector3f>(3), views, options,
                                    &displacements)
                   .ok());
}

TEST(Detail, FillsHolesInTimeThenInSpace) {
  const TriangleMesh base = MakeGridPlane(1.0f, 4, 0.0f);
  const RegularSubdivision lattice = PlaneLattice(base);
  const SampleGraph graph = SampleGraph::Build(lattice);
  const std::size_t samples = lattice.samples().size();
  ASSERT_EQ(graph.offsets.size(), samples + 1);
  std::vector<std::vector<float>> frames(3, std::vector<float>(samples, 1.0f));
  // Sample 5: measured 1 before and 3 after, missing in the middle frame (neighbours 1).
  frames[2][5] = 3.0f;
  frames[1][5] = kNoHit;
  // Sample 7: never measured in the group; its neighbours are all 1.
  for (auto& f : frames) f[7] = kNoHit;
  std::vector<float> last_measured;
  const std::size_t filled = FillDisplacementGroup(graph, &last_measured, &frames);
  EXPECT_EQ(filled, 4u);
  EXPECT_NEAR(frames[1][5], (1.0f + 3.0f + 1.0f) / 3.0f, 1e-6f);
  for (auto& f : frames) EXPECT_NEAR(f[7], 1.0f, 1e-6f);
  EXPECT_EQ(last_measured[5], 3.0f);
  EXPECT_TRUE(std::isnan(last_measured[7]));
  // A group that measured nothing: the previous group's last measurements, then zero.
  std::vector<std::vector<float>> empty(2, std::vector<float>(samples, kNoHit));
  FillDisplacementGroup(graph, &last_measured, &empty);
  EXPECT_NEAR(empty[0][5], 3.0f, 1e-6f);
  for (auto& f : empty) {
    for (float d : f) EXPECT_FALSE(std::isnan(d));
  }
}

// Colour's fill: every sample a value reaches spreads from its valued neighbours (no sample
// of a wide hole takes 0), and a part of the lattice apart from every value takes the frame's
// mean. The displacements' default seeding may give a wide hole's far samples 0.
TEST(Detail, ColourFillSpreadsThroughWideHolesAndGivesApartPartsTheMean) {
  TriangleMesh base = MakeGridPlane(1.0f, 4, 0.0f);
  const std::size_t plane_vertices = base.vertex_count();
  // A second plane, apart from the first: no lattice edge joins them.
  const TriangleMesh apart = MakeGridPlane(1.0f, 2, 5.0f);
  base.positions.insert(base.positions.end(), apart.positions.begin(), apart.positions.end());
  base.normals.insert(base.normals.end(), apart.normals.begin(), apart.normals.end());
  for (const Triangle& t : apart.triangles) {
    base.triangles.push_back({t[0] + static_cast<std::uint32_t>(plane_vertices),
                              t[1] + static_cast<std::uint32_t>(plane_vertices),
                              t[2] + static_cast<std::uint32_t>(plane_vertices)});
  }
  const RegularSubdivision lattice = PlaneLattice(base);
  const SampleGraph graph = SampleGraph::Build(lattice);
  const std::size_t samples = lattice.samples().size();
  // Valued: the first plane's samples with x below its middle (50 and 150); the rest of the
  // first plane is a wide hole; the second plane has no value at all.
  std::vector<std::vector<float>> frames(1, std::vector<float>(samples, kNoHit));
  int valued = 0;
  std::vector<bool> on_first_plane(samples, false);
  for (std::size_t s = 0; s < samples; ++s) {
    const auto& sample = lattice.samples()[s];
    const Triangle& t = base.triangles[sample.triangle];
    on_first_plane[s] = t[0] < plane_vertices;
    const Eigen::Vector3f p = (1 - sample.b1 - sample.b2) * base.positions[t[0]] +
                              sample.b1 * base.positions[t[1]] + sample.b2 * base.positions[t[2]];
    if (on_first_plane[s] && p.x() < -0.2f) {
      frames[0][s] = p.y() < 0 ? 50.0f : 150.0f;
      ++valued;
    }
  }
  ASSERT_GT(valued, 0);
  std::vector<float> last_measured;
  const UnreachedFill colour_fill{.spread_everywhere = true, .frame_mean = true, .no_values = 128};
  FillDisplacementGroup(graph, &last_measured, &frames, colour_fill);
  int apart_samples = 0;
  for (std::size_t s = 0; s < samples; ++s) {
    if (on_first_plane[s]) {
      EXPECT_GE(frames[0][s], 50.0f) << s;  // spread from the values, never 0
      EXPECT_LE(frames[0][s], 150.0f) << s;
    } else {
      ++apart_samples;
    }
  }
  ASSERT_GT(apart_samples, 0);
  // The apart plane takes one value, a mean of the frame's values (50 and 150, and the first
  // ring around them), not 0 or `no_values`.
  std::optional<float> apart_value;
  for (std::size_t s = 0; s < samples; ++s) {
    if (on_first_plane[s]) continue;
    if (!apart_value) apart_value = frames[0][s];
    EXPECT_EQ(frames[0][s], *apart_value) << s;
  }
  EXPECT_GT(*apart_value, 50.0f);
  EXPECT_LT(*apart_value, 150.0f);
  EXPECT_NE(*apart_value, 128.0f);
  // With no value anywhere, `no_values`.
  std::vector<std::vector<float>> none(1, std::vector<float>(samples, kNoHit));
  std::vector<float> fresh;
  FillDisplacementGroup(graph, &fresh, &none, colour_fill);
  for (float v : none[0]) EXPECT_EQ(v, 128.0f);
}

}  // namespace
}  // namespace meshvid
