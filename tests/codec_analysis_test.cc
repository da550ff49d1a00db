// The encoder's analysis stages: normal shooting, rigid fitting, the multi-frame
// segmentation, patch tracking, blend weights, track smoothing, displacement measurement and hole filling.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <algorithm>

#include "codec/enc/detail.h"
#include "codec/enc/motion_blend.h"
#include "codec/enc/normal_shooting.h"
#include "codec/enc/patch_tracking.h"
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

TEST(Segmentation, FindsNoSegmentWhenTheBaseMissesTheData) {
  const TwoBodies scene(3);
  TriangleMesh far = scene.base;
  for (auto& p : far.positions) p += Eigen::Vector3f(10, 0, 0);
  auto result = SegmentPiecewiseRigid(far, scene.Targets(), TestSegmentationOptions());
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  EXPECT_EQ(result->segment_count, 0);
  EXPECT_TRUE(std::all_of(result->labels.begin(), result->labels.end(),
                          [](std::int32_t label) { return label == kUnregistered; }));
  SegmentationOptions bad = TestSegmentationOptions();
  bad.tolerance = 0;
  EXPECT_FALSE(SegmentPiecewiseRigid(scene.base, scene.Targets(), bad).ok());
}

/// Labels with the still body as segment 0 and the moving one unregistered.
std::vector<std::int32_t> StillBodyOnly(const TwoBodies& scene) {
  std::vector<std::int32_t> labels(scene.base.vertex_count(), kUnregistered);
  for (std::size_t v = 0; v < scene.first_body_vertices; ++v) labels[v] = 0;
  return labels;
}

TEST(PatchTracking, SplitsUnregisteredRegionsIntoConnectedPatches) {
  const TwoBodies scene(1);
  std::vector<std::int32_t> labels = StillBodyOnly(scene);
  PatchTrackingOptions options;
  options.patch_vertices = 40;
  const std::size_t free = scene.base.vertex_count() - scene.first_body_vertices;
  const int total = PartitionUnregistered(scene.base, 1, 12, options, &labels);
  EXPECT_EQ(total - 1, int(free / 40));
  std::vector<std::size_t> sizes(total, 0);
  for (std::size_t v = 0; v < labels.size(); ++v) {
    if (v < scene.first_body_vertices) {
      ASSERT_EQ(labels[v], 0) << "segment vertices keep their label";
    } else {
      ASSERT_GE(labels[v], 1) << "vertex " << v << " joined no patch";
      ++sizes[labels[v]];
    }
  }
  for (int p = 1; p < total; ++p) {
    EXPECT_GT(sizes[p], 10u) << "patch " << p;
    EXPECT_LT(sizes[p], 100u) << "patch " << p;
  }
  // Every patch is connected: a flood fill from one member reaches all of them.
  const auto neighbours = VertexNeighbours(scene.base);
  for (int p = 1; p < total; ++p) {
    std::vector<char> seen(labels.size(), 0);
    std::vector<std::uint32_t> stack;
    for (std::uint32_t v = 0; v < labels.size() && stack.empty(); ++v) {
      if (labels[v] == p) stack.push_back(v), seen[v] = 1;
    }
    std::size_t reached = 0;
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      ++reached;
      for (std::uint32_t w : neighbours[v]) {
        if (labels[w] == p && !seen[w]) seen[w] = 1, stack.push_back(w);
      }
    }
    EXPECT_EQ(reached, sizes[p]) << "patch " << p << " is in pieces";
  }
  // The segment budget caps the patches; regions below the minimum stay unregistered.
  labels = StillBodyOnly(scene);
  options.max_segments = 4;
  EXPECT_EQ(PartitionUnregistered(scene.base, 1, 12, options, &labels), 4);
  labels = StillBodyOnly(scene);
  EXPECT_EQ(PartitionUnregistered(scene.base, 1, int(free) + 1, options, &labels), 1);
  EXPECT_EQ(labels.back(), kUnregistered);
}

TEST(PatchTracking, PatchesFollowAMovingBodyTogether) {
  const int frames = 12;
  const TwoBodies scene(frames);
  std::vector<std::int32_t> labels = StillBodyOnly(scene);
  PatchTrackingOptions options;
  options.patch_vertices = 40;
  const int total = PartitionUnregistered(scene.base, 1, 12, options, &labels);
  ASSERT_GT(total, 3);
  std::vector<std::vector<RigidTransform>> transforms(frames, std::vector<RigidTransform>(1));
  const Status status = TrackPatches(scene.base, labels, 1, total, scene.Targets(),
                                     TestSegmentationOptions(), options, &transforms);
  ASSERT_TRUE(status.ok()) << status.ToString();
  float worst = 0;
  for (int f = 0; f < frames; ++f) {
    ASSERT_EQ(transforms[f].size(), std::size_t(total));
    EXPECT_EQ(transforms[f][0].translation.norm(), 0.0f) << "the fixed segment is kept";
    const RigidTransform truth = TwoBodies::MovingAt(f);
    for (std::size_t v = scene.first_body_vertices; v < labels.size(); ++v) {
      const Eigen::Vector3f& p = scene.base.positions[v];
      worst = std::max(worst, (transforms[f][labels[v]].Apply(p) - truth.Apply(p)).norm());
    }
  }
  // The body turns by 0.9 rad and rises by 0.17 over the frames; every vertex stays within
  // the segmentation tolerance (0.01) of where it belongs.
  EXPECT_LT(worst, 0.01f);
  // Mismatched inputs are reported, not guessed at.
  std::vector<std::vector<RigidTransform>> short_tracks(frames - 1);
  EXPECT_FALSE(TrackPatches(scene.base, labels, 1, total, scene.Targets(),
                            TestSegmentationOptions(), options, &short_tracks)
                   .ok());
}

TEST(PatchTracking, PatchesMovingWithASegmentJoinIt) {
  const int frames = 8;
  const TwoBodies scene(frames);
  // Segment 0: the still body; segment 1: the moving body's half beyond x = 1; the other
  // half is patched and tracked, and should rejoin segment 1 (and only it).
  std::vector<std::int32_t> labels = StillBodyOnly(scene);
  for (std::size_t v = scene.first_body_vertices; v < labels.size(); ++v) {
    if (scene.base.positions[v].x() > 1.0f) labels[v] = 1;
  }
  std::vector<std::vector<RigidTransform>> transforms(frames);
  for (int f = 0; f < frames; ++f) transforms[f] = {RigidTransform{}, TwoBodies::MovingAt(f)};
  PatchTrackingOptions options;
  options.patch_vertices = 20;
  const int total = PartitionUnregistered(scene.base, 2, 12, options, &labels);
  ASSERT_GT(total, 3);
  ASSERT_TRUE(TrackPatches(scene.base, labels, 2, total, scene.Targets(),
                           TestSegmentationOptions(), options, &transforms)
                  .ok());
  const int merged = MergePatchesIntoSegments(scene.base, 2, total, TestSegmentationOptions(),
                                              &labels, &transforms);
  EXPECT_EQ(merged, 2);
  for (const auto& frame : transforms) EXPECT_EQ(frame.size(), 2u);
  for (std::size_t v = 0; v < labels.size(); ++v) {
    ASSERT_EQ(labels[v], v < scene.first_body_vertices ? 0 : 1) << "vertex " << v;
  }
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
  SmoothTracks(2, {}, &steady);
  for (int f = 0; f < 9; ++f) {
    EXPECT_LT(steady[f][0].rotation.angularDistance(tracks[f][0].rotation), 1e-4f);
    EXPECT_LT((steady[f][0].translation - tracks[f][0].translation).norm(), 1e-5f);
  }
  auto jittery = tracks;
  jittery[4][0].translation.y() = 0.03f;
  SmoothTracks(1, {}, &jittery);
  EXPECT_NEAR(jittery[4][0].translation.y(), 0.01f, 1e-5f);
}

TEST(MotionBlend, SmoothingKeepsAPieceFarFromTheOriginInPlace) {
  // A piece 28 units from the origin turning about its own centre, 0.1 rad a frame (a steady
  // turn), and one jittering by +-0.1 rad about it (an ill-posed piece sliding along itself).
  // Smoothed about the centre, the steady turn stays as solved and the jitter leaves the
  // centre where it is; averaged about the origin, both moved it by about 0.09.
  const Eigen::Vector3f centre(26.0f, 0.6f, 8.8f);
  const Eigen::Vector3f axis = Eigen::Vector3f(0.3f, 1.0f, 0.2f).normalized();
  auto turn_about_centre = [&](float angle) {
    RigidTransform t;
    t.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(angle, axis));
    t.translation = centre - t.rotation * centre;
    return t;
  };
  std::vector<std::vector<RigidTransform>> steady(3), jittery(3);
  for (int f = 0; f < 3; ++f) {
    steady[f] = {turn_about_centre(0.1f * f)};
    jittery[f] = {turn_about_centre(f == 1 ? 0.1f : f == 2 ? -0.1f : 0.0f)};
  }
  const std::vector<Eigen::Vector3f> centres = {centre};
  const RigidTransform solved = steady[1][0];
  SmoothTracks(1, centres, &steady);
  SmoothTracks(1, centres, &jittery);
  const Eigen::Vector3f corner = centre + Eigen::Vector3f(0.3f, -0.2f, 0.1f);
  EXPECT_LT((steady[1][0].Apply(corner) - solved.Apply(corner)).norm(), 1e-4f);
  EXPECT_LT((jittery[1][0].Apply(centre) - centre).norm(), 1e-4f);
  EXPECT_LT(jittery[1][0].rotation.angularDistance(Eigen::Quaternionf::Identity()), 1e-4f);
}

TEST(MotionBlend, PieceCentresAreTheirVerticesCentroids) {
  const std::vector<Eigen::Vector3f> positions = {{0, 0, 0}, {2, 0, 0}, {0, 4, 0}, {0, 0, 6}};
  const std::vector<std::int32_t> labels = {0, 0, 1, -1};
  const std::vector<Eigen::Vector3f> centres = PieceCentres(positions, labels, 3);
  ASSERT_EQ(centres.size(), 3u);
  EXPECT_LT((centres[0] - Eigen::Vector3f(1, 0, 0)).norm(), 1e-6f);
  EXPECT_LT((centres[1] - Eigen::Vector3f(0, 4, 0)).norm(), 1e-6f);
  // A piece without vertices: the centroid of them all.
  EXPECT_LT((centres[2] - Eigen::Vector3f(0.5f, 1, 1.5f)).norm(), 1e-6f);
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
