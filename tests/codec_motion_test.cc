// Tests of the motion model and its coding: posing, quantisation bounds, damaged payloads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include "codec/common/compression.h"
#include "codec/common/deformation_graph.h"
#include "codec/common/motion.h"
#include "codec/dec/motion_decoder.h"
#include "codec/enc/coding/motion_encoder.h"

namespace meshvid {
namespace {

RigidTransform MakeTransform(float angle, const Eigen::Vector3f& axis, const Eigen::Vector3f& t) {
  RigidTransform r;
  r.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(angle, axis.normalized()));
  r.translation = t;
  return r;
}

TEST(MotionTest, PoseBlendsSegmentTransforms) {
  MotionModel model;
  model.segment_count = 2;
  model.blends.resize(3);
  model.blends[0] = {{{{0, 1.0f}}}, 1};
  model.blends[1] = {{{{1, 1.0f}}}, 1};
  model.blends[2] = {{{{0, 0.5f}, {1, 0.5f}}}, 2};
  ASSERT_TRUE(ValidateMotionModel(model, 3).ok());
  const std::vector<RigidTransform> transforms = {
      MakeTransform(0, Eigen::Vector3f::UnitZ(), {1, 0, 0}),
      MakeTransform(float(M_PI / 2), Eigen::Vector3f::UnitZ(), {0, 0, 0})};
  const std::vector<Eigen::Vector3f> base = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}};
  std::vector<Eigen::Vector3f> posed;
  PoseVertices(model, transforms, base, &posed);
  EXPECT_TRUE(posed[0].isApprox(Eigen::Vector3f(2, 0, 0)));
  EXPECT_TRUE(posed[1].isApprox(Eigen::Vector3f(0, 1, 0), 1e-6f));
  EXPECT_TRUE(posed[2].isApprox(Eigen::Vector3f(1, 0.5f, 0), 1e-6f));

  model.blends[2].influences[1].weight = 0.3f;
  EXPECT_EQ(ValidateMotionModel(model, 3).code(), StatusCode::kCorrupt);
  model.blends[2].influences[1] = {2, 0.5f};
  EXPECT_EQ(ValidateMotionModel(model, 3).message(), "motion: vertex 2 uses segment 2 of 2");
}

TEST(MotionTest, ModelRoundTripsWithWeightsSummingToOne) {
  MotionModel model;
  model.segment_count = 5;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.05f, 1.0f);
  for (int v = 0; v < 500; ++v) {
    VertexBlend blend;
    blend.count = 1 + v % kMaxInfluences;
    float sum = 0;
    for (int i = 0; i < blend.count; ++i) {
      blend.influences[i] = {static_cast<std::uint32_t>((v + i) % 5), uniform(rng)};
      sum += blend.influences[i].weight;
    }
    for (int i = 0; i < blend.count; ++i) blend.influences[i].weight /= sum;
    model.blends.push_back(blend);
  }
  const MotionQuantization quantization;
  auto payload = EncodeMotionModel(model, quantization);
  ASSERT_TRUE(payload.ok()) << payload.status().ToString();
  auto decoded = DecodeMotionModel(*payload, 500);
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  EXPECT_EQ(decoded->model.segment_count, 5u);
  for (int v = 0; v < 500; ++v) {
    const VertexBlend& a = model.blends[v];
    const VertexBlend& b = decoded->model.blends[v];
    ASSERT_EQ(a.count, b.count);
    float sum = 0;
    for (int i = 0; i < a.count; ++i) {
      EXPECT_EQ(a.influences[i].segment, b.influences[i].segment);
      EXPECT_NEAR(a.influences[i].weight, b.influences[i].weight, 2e-4f);
      sum += b.influences[i].weight;
    }
    EXPECT_NEAR(sum, 1.0f, 1e-6f);
  }
  EXPECT_EQ(DecodeMotionModel(*payload, 499).status().code(), StatusCode::kCorrupt);
  EXPECT_TRUE(decoded->model.surface_triangles.empty());
  // Without a mask: motion_version 1, which has no mask_triangle_count (spec/mvid-codec.md 2.1).
  EXPECT_EQ((*payload)[0], 1);
}

TEST(MotionTest, SurfaceMaskRoundTripsAndMustMatchTheBase) {
  MotionModel model = SingleSegmentModel(10);
  model.surface_triangles = {1, 0, 0, 1, 1, 1, 0, 1, 0, 0, 1};  // 11 triangles: 2 bytes
  auto payload = EncodeMotionModel(model, MotionQuantization{});
  ASSERT_TRUE(payload.ok()) << payload.status().ToString();
  EXPECT_EQ((*payload)[0], 2);  // motion_version 2: the one with a mask
  auto decoded = DecodeMotionModel(*payload, 10, 11);
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  EXPECT_EQ(decoded->model.surface_triangles, model.surface_triangles);
  // The same model without its mask is 4 bytes of header shorter (no mask_triangle_count).
  MotionModel unmasked = model;
  unmasked.surface_triangles.clear();
  auto plain = EncodeMotionModel(unmasked, MotionQuantization{});
  ASSERT_TRUE(plain.ok()) << plain.status().ToString();
  EXPECT_EQ((*plain)[0], 1);
  auto plain_decoded = DecodeMotionModel(*plain, 10, 11);
  ASSERT_TRUE(plain_decoded.ok()) << plain_decoded.status().ToString();
  EXPECT_TRUE(plain_decoded->model.surface_triangles.empty());
  // A mask for another base mesh is corrupt input.
  EXPECT_EQ(DecodeMotionModel(*payload, 10, 12).status().code(), StatusCode::kCorrupt);
}

TEST(MotionTest, DeformationNodesRoundTripAndTheirBlendsAreDerivedFromTheBase) {
  // A 9 x 9 grid of unit squares; nodes 3 apart along the edges.
  TriangleMesh grid;
  for (int y = 0; y < 9; ++y) {
    for (int x = 0; x < 9; ++x) grid.positions.emplace_back(float(x), float(y), 0.0f);
  }
  for (std::uint32_t y = 0; y < 8; ++y) {
    for (std::uint32_t x = 0; x < 8; ++x) {
      const std::uint32_t a = y * 9 + x;
      grid.triangles.push_back({a, a + 1, a + 10});
      grid.triangles.push_back({a, a + 10, a + 9});
    }
  }
  const auto neighbours = VertexNeighbours(grid);
  MotionModel model;
  model.node_spacing = 3;
  model.node_vertices = SampleDeformationNodes(grid, neighbours, model.node_spacing);
  model.segment_count = static_cast<std::uint32_t>(model.node_vertices.size());
  ASSERT_TRUE(CompleteNodeBlends(grid, &model).ok());
  model.surface_triangles.assign(grid.triangle_count(), 1);
  model.surface_triangles[5] = 0;
  auto payload = EncodeMotionModel(model, MotionQuantization{});
  ASSERT_TRUE(payload.ok()) << payload.status().ToString();
  EXPECT_EQ((*payload)[0], 3);  // motion_version 3: nodes, not blends
  // A u32 per node, not 25 bytes per vertex.
  EXPECT_LT(payload->size(), 30 + 4 * model.node_vertices.size() + 32);
  auto decoded = DecodeMotionModel(*payload, grid.vertex_count(), grid.triangle_count());
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  EXPECT_EQ(decoded->model.node_vertices, model.node_vertices);
  EXPECT_EQ(decoded->model.node_spacing, model.node_spacing);
  EXPECT_EQ(decoded->model.surface_triangles, model.surface_triangles);
  EXPECT_TRUE(decoded->model.blends.empty());
  ASSERT_TRUE(CompleteNodeBlends(grid, &decoded->model).ok());
  for (std::size_t v = 0; v < grid.vertex_count(); ++v) {
    const VertexBlend& a = model.blends[v];
    const VertexBlend& b = decoded->model.blends[v];
    ASSERT_EQ(a.count, b.count) << "vertex " << v;
    for (int k = 0; k < a.count; ++k) {
      EXPECT_EQ(a.influences[k].segment, b.influences[k].segment);
      EXPECT_EQ(a.influences[k].weight, b.influences[k].weight);
    }
  }
  // A node vertex past the base, a spacing that is not finite, a vertex no node reaches.
  MotionModel bad = model;
  bad.node_vertices.back() = 81;
  auto out_of_range = EncodeMotionModel(bad, MotionQuantization{});
  ASSERT_TRUE(out_of_range.ok());
  EXPECT_EQ(DecodeMotionModel(*out_of_range, 81, 128).status().code(), StatusCode::kCorrupt);
  bad = model;
  bad.node_spacing = std::numeric_limits<float>::quiet_NaN();
  auto nan = EncodeMotionModel(bad, MotionQuantization{});
  ASSERT_TRUE(nan.ok());
  EXPECT_EQ(DecodeMotionModel(*nan, 81, 128).status().code(), StatusCode::kCorrupt);
  bad = model;
  bad.node_spacing = 0.5f;  // reaches 1.5: the grid's far corners have no node within it
  EXPECT_EQ(CompleteNodeBlends(grid, &bad).code(), StatusCode::kCorrupt);
  bad = model;
  bad.node_vertices[1] = bad.node_vertices[0];
  EXPECT_EQ(CompleteNodeBlends(grid, &bad).code(), StatusCode::kCorrupt);
}

TEST(MotionTest, TransformsRoundTripWithinTheStatedSteps) {
  MotionQuantization quantization;
  quantization.rotation_step = 1e-4f;
  quantization.translation_step = 1e-4f;
  std::vector<std::vector<RigidTransform>> frames;
  for (int f = 0; f < 40; ++f) {
    frames.push_back({MakeTransform(0.02f * f, {0, 1, 0}, {0.01f * f, 0.5f, -0.2f}),
                      MakeTransform(3.0f, {1, 1, 0}, {0.0f, 0.0f, 0.001f * f * f})});
  }
  auto encoded = EncodeTransforms(frames, quantization);
  ASSERT_TRUE(encoded.ok());
  auto decoded = DecodeTransforms(encoded->bytes, 40, 2, quantization);
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  // A point at distance 1 moves by at most sqrt(3) steps of rotation and of translation.
  const float bound = std::sqrt(3.0f) * 1e-4f;
  const Eigen::Vector3f probe(0.6f, -0.8f, 0.0f);
  for (int f = 0; f < 40; ++f) {
    for (int s = 0; s < 2; ++s) {
      const RigidTransform& d = (*decoded)[f][s];
      EXPECT_LE((d.Apply(probe) - frames[f][s].Apply(probe)).norm(), 2 * bound);
      EXPECT_TRUE(d.rotation.coeffs().isApprox(encoded->decoded[f][s].rotation.coeffs()));
      EXPECT_EQ(d.translation, encoded->decoded[f][s].translation);
    }
  }
  // Smooth tracks cost far less than the 24 bytes per transform of the raw body.
  EXPECT_LT(encoded->bytes.size(), 40u * 2 * 24 / 3);
}

TEST(MotionTest, TransformsQuantisedAboutAPivotKeepTheBoundNearIt) {
  // A segment far from the origin, reaching 0.1 from its pivot: the rotation step its reach
  // allows is 25 times the one a point 10 away needs (a quarter of the bound each).
  MotionQuantization fine;
  fine.translation_step = 1e-4f;
  fine.rotation_step = 1e-4f / 10;
  const float reach = 0.1f;
  MotionQuantization coarse = fine;
  coarse.rotation_step = RotationStepForReach(fine, reach);
  EXPECT_FLOAT_EQ(coarse.rotation_step, 2.5e-4f);
  const Eigen::Vector3f pivot(6.0f, -5.0f, 4.0f);
  // A tracked segment: its pose jitters from frame to frame by a few millimetres and degrees.
  std::mt19937 random(7);
  std::normal_distribution<float> jitter(0.0f, 0.02f);
  std::vector<std::vector<RigidTransform>> frames;
  for (int f = 0; f < 20; ++f) {
    const Eigen::Vector3f axis(1 + jitter(random), 2 + jitter(random), 3 + jitter(random));
    const Eigen::Vector3f t(0.02f * f + 0.1f * jitter(random), 0.1f, -0.3f);
    frames.push_back({MakeTransform(0.013f * f + jitter(random), axis, t)});
  }
  const std::vector<Eigen::Vector3f> pivots = {pivot};
  auto about_pivot = EncodeTransforms(frames, coarse, pivots);
  ASSERT_TRUE(about_pivot.ok());
  auto decoded = DecodeTransforms(about_pivot->bytes, 20, 1, coarse);
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  // Within the segment's reach a point moves by at most sqrt(3) / 2 steps of translation for
  // each rounding, as a point within 10 of the origin does at the fine steps.
  const float bound = std::sqrt(3.0f) * fine.translation_step;
  const Eigen::Vector3f offsets[] = {{0, 0, 0}, {0.1f, 0, 0}, {0, -0.06f, 0.08f}};
  float about_origin_error = 0;
  auto about_origin = EncodeTransforms(frames, coarse);
  ASSERT_TRUE(about_origin.ok());
  for (int f = 0; f < 20; ++f) {
    for (const Eigen::Vector3f& offset : offsets) {
      const Eigen::Vector3f p = pivot + offset;
      EXPECT_LE(((*decoded)[f][0].Apply(p) - frames[f][0].Apply(p)).norm(), bound);
      about_origin_error =
          std::max(about_origin_error,
                   (about_origin->decoded[f][0].Apply(p) - frames[f][0].Apply(p)).norm());
    }
  }
  // Rounded about the origin, the same coarse rotation step moves these points 5 times as far.
  EXPECT_GT(about_origin_error, 5 * bound);
  // The coarse rotation step costs fewer bytes than the fine one the origin needs.
  auto at_fine_steps = EncodeTransforms(frames, fine);
  ASSERT_TRUE(at_fine_steps.ok());
  EXPECT_LT(about_pivot->bytes.size(), at_fine_steps->bytes.size());
  EXPECT_FALSE(EncodeTransforms(frames, coarse, std::vector<Eigen::Vector3f>(2)).ok());
}

TEST(MotionTest, PivotsAreTheCentresOfTheVerticesEachSegmentMoves) {
  MotionModel model;
  model.segment_count = 3;  // segment 2 moves no vertex
  model.blends.resize(4);
  model.blends[0] = {{{{0, 1.0f}}}, 1};
  model.blends[1] = {{{{0, 0.5f}, {1, 0.5f}}}, 2};
  model.blends[2] = {{{{1, 1.0f}}}, 1};
  model.blends[3] = {{{{1, 1.0f}}}, 1};
  const std::vector<Eigen::Vector3f> positions = {{0, 0, 0}, {2, 0, 0}, {2, 4, 0}, {2, 0, 3}};
  const MotionPivots pivots = FindMotionPivots(model, positions);
  ASSERT_EQ(pivots.pivots.size(), 3u);
  EXPECT_TRUE(pivots.pivots[0].isApprox(Eigen::Vector3f(1, 0, 0)));
  EXPECT_TRUE(pivots.pivots[1].isApprox(Eigen::Vector3f(2, 2, 1.5f)));
  EXPECT_EQ(pivots.pivots[2], Eigen::Vector3f::Zero());
  EXPECT_FLOAT_EQ(pivots.reach, 2.5f);  // half the diagonal of segment 1's 0 x 4 x 3 box
  // The step a reach allows: never finer than the one given, never 0.5 radian or more.
  MotionQuantization q;
  q.translation_step = 0.01f;
  q.rotation_step = 0.0001f;
  EXPECT_FLOAT_EQ(RotationStepForReach(q, 2.5f), 0.001f);
  EXPECT_FLOAT_EQ(RotationStepForReach(q, 100.0f), 0.0001f);
  EXPECT_FLOAT_EQ(RotationStepForReach(q, 0.0f), 0.5f);
  EXPECT_FLOAT_EQ(RotationStepForReach(q, 1e-6f), 0.5f);
}

/// `payload` (EncodeTransforms' byte planes) with its deltas' bytes together again, as
/// side_info_version 1 stored them.
std::vector<std::uint8_t> AsInterleaved(const std::vector<std::uint8_t>& payload,
                                        std::size_t transforms) {
  const std::size_t values = transforms * 6;
  auto planes = DecompressBlock(std::span(payload).subspan(8), values * 4, "transforms");
  EXPECT_TRUE(planes.ok());
  std::vector<std::uint8_t> out(payload.begin(), payload.begin() + 8);  // the two counts
  const std::vector<std::uint8_t> compressed = CompressBlock(JoinBytePlanes(*planes));
  out.insert(out.end(), compressed.begin(), compressed.end());
  return out;
}

TEST(MotionTest, TransformsDecodeAlikeFromEitherByteOrder) {
  // 60 nodes of a bending strip, 30 frames: each node turns and moves a little every frame.
  constexpr int kFrames = 30, kNodes = 60;
  std::vector<std::vector<RigidTransform>> frames(kFrames);
  for (int f = 0; f < kFrames; ++f) {
    for (int n = 0; n < kNodes; ++n) {
      const float bend = 0.004f * f * n;
      frames[f].push_back(MakeTransform(bend, {0, 0, 1}, {0.002f * f, 0.01f * n * bend, 0}));
    }
  }
  const MotionQuantization quantization;
  auto planes = EncodeTransforms(frames, quantization);
  ASSERT_TRUE(planes.ok());
  const std::vector<std::uint8_t> interleaved = AsInterleaved(planes->bytes, kFrames * kNodes);
  auto from_planes = DecodeTransforms(planes->bytes, kFrames, kNodes, quantization);
  auto from_interleaved = DecodeTransforms(interleaved, kFrames, kNodes, quantization,
                                           TransformByteOrder::kInterleaved);
  ASSERT_TRUE(from_planes.ok()) << from_planes.status().ToString();
  ASSERT_TRUE(from_interleaved.ok()) << from_interleaved.status().ToString();
  for (int f = 0; f < kFrames; ++f) {
    for (int n = 0; n < kNodes; ++n) {
      const RigidTransform& a = (*from_planes)[f][n];
      const RigidTransform& b = (*from_interleaved)[f][n];
      EXPECT_EQ(a.translation, b.translation) << f << " " << n;
      EXPECT_EQ(a.rotation.coeffs(), b.rotation.coeffs()) << f << " " << n;
      EXPECT_EQ(a.translation, planes->decoded[f][n].translation);
    }
  }
  // The planes gather the deltas' zero high bytes into runs: fewer bytes (bench figures in
  // spec/mvid-codec.md's change log, 2.4).
  EXPECT_LT(planes->bytes.size(), interleaved.size());
  std::printf("%d transforms: %zu bytes as byte planes, %zu interleaved\n", kFrames * kNodes,
              planes->bytes.size(), interleaved.size());
}

TEST(MotionTest, DamagedPayloadsFailCleanly) {
  const std::vector<std::vector<RigidTransform>> frames(8, {RigidTransform{}, RigidTransform{}});
  auto encoded = EncodeTransforms(frames, MotionQuantization{});
  ASSERT_TRUE(encoded.ok());
  const std::vector<std::uint8_t>& bytes = encoded->bytes;
  EXPECT_EQ(DecodeTransforms(bytes, 9, 2, {}).status().code(), StatusCode::kCorrupt);
  EXPECT_EQ(DecodeTransforms(bytes, 8, 3, {}).status().code(), StatusCode::kCorrupt);
  for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
    EXPECT_FALSE(DecodeTransforms(std::span(bytes.data(), cut), 8, 2, {}).ok()) << cut;
  }
  auto model = EncodeMotionModel(SingleSegmentModel(10), MotionQuantization{});
  ASSERT_TRUE(model.ok());
  for (std::size_t cut = 0; cut < model->size(); ++cut) {
    EXPECT_FALSE(DecodeMotionModel(std::span(model->data(), cut), 10).ok()) << cut;
  }
}

}  // namespace
}  // namespace meshvid
