// Tests of the regular subdivision lattice: counts, prefix order, watertightness, geometry.
#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "codec/common/subdivision.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

/// The unit octahedron: 6 vertices, 12 edges, 8 outward-facing triangles.
TriangleMesh Octahedron() {
  TriangleMesh mesh;
  mesh.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  mesh.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                    {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return mesh;
}

TEST(RegularSubdivisionTest, SampleAndTriangleCountsFollowTheLattice) {
  const TriangleMesh base = Octahedron();
  auto subdivision = RegularSubdivision::Create(base, 3);
  ASSERT_TRUE(subdivision.ok()) << subdivision.status().ToString();
  for (int level = 0; level <= 3; ++level) {
    const std::size_t n = std::size_t{1} << level;
    // V + E (n - 1) + F (n - 1)(n - 2) / 2
    EXPECT_EQ(subdivision->sample_count(level), 6 + 12 * (n - 1) + 8 * (n - 1) * (n - 2) / 2);
    EXPECT_EQ(subdivision->Triangles(level).size(), 8 * n * n);
  }
  EXPECT_EQ(subdivision->samples().size(), subdivision->sample_count(3));
}

TEST(RegularSubdivisionTest, EveryLevelIsAClosedOrientedSurfaceOverItsPrefix) {
  auto subdivision = RegularSubdivision::Create(Octahedron(), 3);
  ASSERT_TRUE(subdivision.ok());
  for (int level = 0; level <= 3; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed_edges;
    for (const Triangle& t : subdivision->Triangles(level)) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_LT(t[c], subdivision->sample_count(level));
        ++directed_edges[{t[c], t[(c + 1) % 3]}];
      }
    }
    // Watertight and consistently oriented: every directed edge once, its reverse once.
    for (const auto& [edge, count] : directed_edges) {
      EXPECT_EQ(count, 1);
      EXPECT_EQ(directed_edges.count({edge.second, edge.first}), 1u);
    }
  }
}

TEST(RegularSubdivisionTest, SamplesLieOnTheFlatSurfaceAndDisplaceAlongNormals) {
  const TriangleMesh base = Octahedron();
  auto subdivision = RegularSubdivision::Create(base, 2);
  ASSERT_TRUE(subdivision.ok());
  std::vector<Eigen::Vector3f> normals;
  for (const auto& p : base.positions) normals.push_back(p.normalized());
  std::vector<Eigen::Vector3f> origins, directions;
  EvaluateSampleFrames(*subdivision, 2, base.positions, normals, &origins, &directions);
  ASSERT_EQ(origins.size(), subdivision->sample_count(2));
  std::vector<float> to_sphere;
  for (std::size_t s = 0; s < origins.size(); ++s) {
    // Every point of the octahedron has |x| + |y| + |z| = 1.
    EXPECT_NEAR(origins[s].cwiseAbs().sum(), 1.0f, 1e-6f);
    EXPECT_NEAR(directions[s].norm(), 1.0f, 1e-6f);
    // The displacement that takes the sample along its normal onto the unit sphere.
    const float b = origins[s].dot(directions[s]);
    const float c = origins[s].squaredNorm() - 1.0f;
    to_sphere.push_back(-b + std::sqrt(b * b - c));
  }
  const TriangleMesh sphere = DisplaceSamples(*subdivision, 2, origins, directions, to_sphere);
  ASSERT_TRUE(ValidateMesh(sphere, "sphere").ok());
  for (const auto& p : sphere.positions) EXPECT_NEAR(p.norm(), 1.0f, 1e-5f);
  // Base vertices keep their index and position.
  for (std::size_t v = 0; v < base.vertex_count(); ++v) {
    EXPECT_TRUE(origins[v].isApprox(base.positions[v]));
  }
}

TEST(RegularSubdivisionTest, CoarseLevelsArePrefixesOfFinerOnes) {
  const TriangleMesh base = testing::MakeGridPlane(2.0f, 3);
  auto fine = RegularSubdivision::Create(base, 3);
  auto coarse = RegularSubdivision::Create(base, 1);
  ASSERT_TRUE(fine.ok() && coarse.ok());
  const std::vector<Eigen::Vector3f> normals(base.vertex_count(), Eigen::Vector3f::UnitZ());
  std::vector<Eigen::Vector3f> fine_origins, coarse_origins, directions;
  EvaluateSampleFrames(*fine, 1, base.positions, normals, &fine_origins, &directions);
  EvaluateSampleFrames(*coarse, 1, base.positions, normals, &coarse_origins, &directions);
  ASSERT_EQ(fine_origins.size(), coarse_origins.size());
  for (std::size_t s = 0; s < fine_origins.size(); ++s) {
    EXPECT_TRUE(fine_origins[s].isApprox(coarse_origins[s], 1e-6f)) << "sample " << s;
  }
  EXPECT_EQ(fine->Triangles(1), coarse->Triangles(1));
}

TEST(RegularSubdivisionTest, RejectsBadLevels) {
  EXPECT_EQ(RegularSubdivision::Create(Octahedron(), 7).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(RegularSubdivision::Create(Octahedron(), -1).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_FALSE(RegularSubdivision::Create(TriangleMesh{}, 1).ok());
}

}  // namespace
}  // namespace meshvid
