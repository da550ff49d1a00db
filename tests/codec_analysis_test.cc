// The encoder's analysis stages: normal shooting, rigid fitting, the multi-frame
// segmentation, blend weights, track smoothing, displacement measurement and hole filling.
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "codec/enc/detail.h"
#include "codec/enc/motion_blend.h"
#include "codec/enc/normal_shooting.h"
#include "codec/enc/segmentation.h"
#include "tests/analytic_mvid.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

using testing::MakeGridPlane;
using testing::SphereMesh;

RigidTransform MakeTransform(float angle, const Eigen::Vector3f& axis,
                             const Eigen::Vector3f& translation) {
  RigidTransform t;
  t.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(angle, axis.normalized()));
  t.translation = translation;
  return t;
}

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

/// Two ellipsoids (a sphere's rotation would be invisible), one still, one turning and rising;
/// the data is each frame's posed bodies tessellated differently (so base vertices are not
/// data vertices; the surfaces differ by chords under a millimetre).
struct TwoBodies {
  TriangleMesh base;
  std::size_t first_body_vertices = 0;
  std::vector<std::unique_ptr<ShootingTarget>> targets;
  static RigidTransform MovingAt(int frame) {
    const Eigen::Vector3f centre(1, 0, 0);
    const RigidTransform spin = MakeTransform(0.08f * frame, {0, 1, 1}, Eigen::Vector3f::Zero());
    RigidTransform t;
    t.rotation = spin.rotation;
    t.translation = centre - spin.rotation * centre + Eigen::Vector3f(0, 0.015f * frame, 0);
    return t;
  }
  explicit TwoBodies(int frames) {
    TriangleMesh a = SphereMesh(3), b = SphereMesh(3);
    const Eigen::Vector3f radii(0.3f, 0.12f, 0.2f);
    for (auto& p : a.positions) p = p.cwiseProduct(radii);
    for (auto& p : b.positions) p = p.cwiseProduct(radii) + Eigen::Vector3f(1, 0, 0);
    a.normals.clear();
    b.normals.clear();
    first_body_vertices = a.vertex_count();
    AppendMesh(a, &base);
    AppendMesh(b, &base);
    const TriangleMesh fine = testing::LatLongSphere(48, 96);
    for (int f = 0; f < frames; ++f) {
      TriangleMesh still = fine, moved = fine;
      const RigidTransform moving = MovingAt(f);
      for (auto& p : still.positions) p = p.cwiseProduct(radii);
      for (auto& p : moved.positions) {
        p = moving.Apply(p.cwiseProduct(radii) + Eigen::Vector3f(1, 0, 0));
      }
      TriangleMesh data;
      AppendMesh(still, &data);
      AppendMesh(moved, &data);
      targets.push_back(std::move(ShootingTarget::Create(data).value()));
    }
  }
  std::vector<const ShootingTarget*> Targets() const {
    std::vector<const ShootingTarget*> result;
    for (const auto& t : targets) result.push_back(t.get());
    return result;
  }
};

SegmentationOptions TestSegmentationOptions() {
  SegmentationOptions options;
  options.tolerance = 0.01f;
  options.shot.max_distance = 0.1f;
  options.shot.min_abs_cos = 0.5f;
  return options;
}

TEST(Segmentation, SeparatesTwoRigidBodiesAndRecoversTheirMotion) {
  const int frames = 12;
  const TwoBodies scene(frames);
  auto result = SegmentPiecewiseRigid(scene.base, scene.Targets(), TestSegmentationOptions());
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  ASSERT_EQ(result->segment_count, 2);
  const std::int32_t first_label = result->labels[0];
  const std::int32_t second_label = result->labels[scene.first_body_vertices];
  EXPECT_NE(first_label, second_label);
  for (std::size_t v = 0; v < scene.base.vertex_count(); ++v) {
    ASSERT_EQ(result->labels[v], v < scene.first_body_vertices ? first_label : second_label)
        << "vertex " << v;
  }
  ASSERT_EQ(result->transforms.size(), std::size_t(frames));
  for (int f = 0; f < frames; ++f) {
    const RigidTransform& moving = result->transforms[f][second_label];
    const RigidTransform truth = TwoBodies::MovingAt(f);
    // Compare where both put the moving sphere's centre and a point on it.
    for (const Eigen::Vector3f& p : {Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(1.3f, 0, 0)}) {
      EXPECT_LT((moving.Apply(p) - truth.Apply(p)).norm(), 0.004f) << "frame " << f;
    }
    EXPECT_LT(result->transforms[f][first_label].translation.norm(), 0.004f);
  }
}

TEST(Segmentation, TracksFixedSegmentsThroughANewFrame) {
  const TwoBodies scene(8);
  auto result = SegmentPiecewiseRigid(scene.base, scene.Targets(), TestSegmentationOptions());
  ASSERT_TRUE(result.ok());
  const int moving = result->labels[scene.first_body_vertices];
  // From frame 6's transforms, track into frame 7.
  const auto tracked = TrackSegments(scene.base, result->labels, result->segment_count,
                                     *scene.targets[7], result->transforms[6],
                                     TestSegmentationOptions());
  const Eigen::Vector3f p(1.3f, 0, 0);
  EXPECT_LT((tracked[moving].Apply(p) - TwoBodies::MovingAt(7).Apply(p)).norm(), 0.004f);
}

TEST(Segmentation, FailsClearlyWhenTheBaseMissesTheData) {
  const TwoBodies scene(3);
  TriangleMesh far = scene.base;
  for (auto& p : far.positions) p += Eigen::Vector3f(10, 0, 0);
  auto result = SegmentPiecewiseRigid(far, scene.Targets(), TestSegmentationOptions());
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.status().message().find("no rigid segment"), std::string::npos);
  SegmentationOptions bad = TestSegmentationOptions();
  bad.tolerance = 0;
  EXPECT_FALSE(SegmentPiecewiseRigid(scene.base, scene.Targets(), bad).ok());
}

TEST(MotionBlend, InterpolatesUnregisteredVerticesBetweenSegments) {
  // A strip of quads along x: left end segment 0, right end segment 1, middle unregistered.
  TriangleMesh strip;
  const int columns = 9;
  for (int i = 0; i < columns; ++i) {
    strip.positions.push_back({float(i), 0, 0});
    strip.positions.push_back({float(i), 1, 0});
  }
  for (int i = 0; i + 1 < columns; ++i) {
    const std::uint32_t a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
    strip.triangles.push_back(Triangle(a, c, d));
    strip.triangles.push_back(Triangle(a, d, b));
  }
  std::vector<std::int32_t> labels(strip.vertex_count(), kUnregistered);
  for (int v : {0, 1, 2, 3}) labels[v] = 0;
  for (int v : {14, 15, 16, 17}) labels[v] = 1;
  const MotionModel model = BlendWeightsFromLabels(strip, labels, 2);
  ASSERT_TRUE(ValidateMotionModel(model, strip.vertex_count()).ok());
  EXPECT_EQ(model.blends[0].count, 1);
  EXPECT_EQ(model.blends[0].influences[0].segment, 0u);
  EXPECT_EQ(model.blends[16].influences[0].segment, 1u);
  // The middle column blends both, about evenly; weights fall off towards the ends.
  const VertexBlend& middle = model.blends[8];
  ASSERT_EQ(middle.count, 2);
  EXPECT_NEAR(middle.influences[0].weight, 0.5f, 0.2f);
  auto weight_of = [&](std::size_t v, std::uint32_t segment) {
    for (int k = 0; k < model.blends[v].count; ++k) {
      if (model.blends[v].influences[k].segment == segment) return model.blends[v].influences[k].weight;
    }
    return 0.0f;
  };
  EXPECT_GT(weight_of(4, 0), weight_of(8, 0));
  EXPECT_GT(weight_of(8, 0), weight_of(12, 0));
}

TEST(MotionBlend, SmoothingKeepsSteadyMotionAndDampsJitter) {
  std::vector<std::vector<RigidTransform>> tracks(9, std::vector<RigidTransform>(1));
  for (int f = 0; f < 9; ++f) {
    tracks[f][0] = MakeTransform(0.05f * f, {0, 0, 1}, {0.01f * f, 0, 0});
  }
  auto steady = tracks;
  SmoothTracks(2, &steady);
  for (int f = 0; f < 9; ++f) {
    EXPECT_LT(steady[f][0].rotation.angularDistance(tracks[f][0].rotation), 1e-4f);
    EXPECT_LT((steady[f][0].translation - tracks[f][0].translation).norm(), 1e-5f);
  }
  auto jittery = tracks;
  jittery[4][0].translation.y() = 0.03f;
  SmoothTracks(1, &jittery);
  EXPECT_NEAR(jittery[4][0].translation.y(), 0.01f, 1e-5f);
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

}  // namespace
}  // namespace meshvid
