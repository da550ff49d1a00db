// Tests of the Draco base-mesh coder.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "codec/dec/base_mesh_decoder.h"
#include "codec/enc/coding/base_mesh_encoder.h"
#include "tests/analytic_mvid.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

TEST(BaseMeshCoderTest, RoundTripKeepsTheMeshWithinQuantisation) {
  const TriangleMesh mesh = testing::MakeGridPlane(2.0f, 20, 0.5f);
  BaseMeshEncoding settings;
  settings.position_bits = 14;
  settings.allow_reorder = true;  // edgebreaker, whatever order it gives back
  auto encoded = EncodeBaseMesh(mesh, settings);
  ASSERT_TRUE(encoded.ok()) << encoded.status().ToString();
  EXPECT_EQ(encoded->decoded.vertex_count(), mesh.vertex_count());
  EXPECT_EQ(encoded->decoded.triangle_count(), mesh.triangle_count());
  EXPECT_LT(encoded->bytes.size(), mesh.vertex_count() * 12 / 4);  // it compresses
  // Draco reorders vertices: every decoded vertex must be near a grid point, and the grid
  // spacing 0.1 is far larger than the quantisation step 2 / 2^14.
  const float step = 2.0f / (1 << 14);
  for (const auto& p : encoded->decoded.positions) {
    const float gx = std::round((p.x() + 1.0f) * 10.0f) / 10.0f - 1.0f;
    const float gy = std::round((p.y() + 1.0f) * 10.0f) / 10.0f - 1.0f;
    EXPECT_NEAR(p.x(), gx, step);
    EXPECT_NEAR(p.y(), gy, step);
    EXPECT_NEAR(p.z(), 0.5f, step);
  }
  EXPECT_NEAR(SurfaceArea(encoded->decoded), 4.0, 1e-3);
  // The decoder reproduces exactly what the encoder computed against.
  auto decoded = DecodeBaseMesh(encoded->bytes);
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(decoded->positions, encoded->decoded.positions);
  EXPECT_EQ(decoded->triangles, encoded->decoded.triangles);
}

TEST(BaseMeshCoderTest, VertexColoursRideWithTheirVerticesWhenAskedFor) {
  TriangleMesh mesh = testing::MakeGridPlane(2.0f, 20, 0.5f);
  // Each vertex's colour is a function of where it is, so it can be checked after Draco has
  // reordered the vertices.
  const auto colour_at = [](const Eigen::Vector3f& p) {
    return Colour(static_cast<std::uint8_t>(std::lround((p.x() + 1.0f) * 100.0f)),
                  static_cast<std::uint8_t>(std::lround((p.y() + 1.0f) * 100.0f)), 7);
  };
  for (const Eigen::Vector3f& p : mesh.positions) mesh.colours.push_back(colour_at(p));
  BaseMeshEncoding settings;
  settings.position_bits = 14;
  settings.allow_reorder = true;
  auto plain = EncodeBaseMesh(mesh, settings);
  settings.code_colours = true;
  auto coloured = EncodeBaseMesh(mesh, settings);
  ASSERT_TRUE(plain.ok() && coloured.ok());
  EXPECT_TRUE(plain->decoded.colours.empty());
  EXPECT_GT(coloured->bytes.size(), plain->bytes.size());
  ASSERT_EQ(coloured->decoded.colours.size(), mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    // Positions are quantised at 2 / 2^14, far less than one colour step (0.01).
    EXPECT_EQ(coloured->decoded.colours[v], colour_at(coloured->decoded.positions[v])) << v;
  }
  // The decoder reads them only when asked: a .mvid base mesh is positions and triangles.
  auto ignored = DecodeBaseMesh(coloured->bytes);
  ASSERT_TRUE(ignored.ok());
  EXPECT_TRUE(ignored->colours.empty());
  auto read = DecodeBaseMesh(coloured->bytes, VertexColours::kRead);
  ASSERT_TRUE(read.ok());
  EXPECT_EQ(read->colours, coloured->decoded.colours);
}

/// Every vertex and triangle of `mesh` is found in `coded` where its maps say.
void ExpectMappedBack(const TriangleMesh& mesh, const EncodedBaseMesh& coded, float step) {
  ASSERT_EQ(coded.vertex_in_decoded.size(), mesh.vertex_count());
  ASSERT_EQ(coded.triangle_in_decoded.size(), mesh.triangle_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3f& moved = coded.decoded.positions[coded.vertex_in_decoded[v]];
    EXPECT_LE((moved - mesh.positions[v]).cwiseAbs().maxCoeff(), step);
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& moved = coded.decoded.triangles[coded.triangle_in_decoded[t]];
    std::array<std::uint32_t, 3> expected;
    for (int c = 0; c < 3; ++c) expected[c] = coded.vertex_in_decoded[mesh.triangles[t][c]];
    std::array<std::uint32_t, 3> got = {moved[0], moved[1], moved[2]};
    std::sort(expected.begin(), expected.end());
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expected) << t;
  }
}

TEST(BaseMeshCoderTest, EdgebreakerOrderIsFoundAgainOrTheOrderIsKept) {
  const TriangleMesh mesh = testing::SphereMesh(4);
  BaseMeshEncoding sequential;
  sequential.try_edgebreaker = false;
  auto in_order = EncodeBaseMesh(mesh, sequential);
  ASSERT_TRUE(in_order.ok());
  EXPECT_TRUE(in_order->vertex_in_decoded.empty());
  ASSERT_EQ(in_order->decoded.vertex_count(), mesh.vertex_count());
  EXPECT_EQ(in_order->decoded.triangles, mesh.triangles);
  const float step = 2.0f / ((1 << 16) - 1);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_LE((in_order->decoded.positions[v] - mesh.positions[v]).cwiseAbs().maxCoeff(), step);
  }
  // By default edgebreaker, smaller, with where every vertex and triangle went.
  auto small = EncodeBaseMesh(mesh);
  ASSERT_TRUE(small.ok());
  EXPECT_LT(small->bytes.size(), in_order->bytes.size() / 2);
  ASSERT_EQ(small->vertex_in_decoded.size(), mesh.vertex_count());
  ASSERT_EQ(small->triangle_in_decoded.size(), mesh.triangle_count());
  ExpectMappedBack(mesh, *small, step);
}

TEST(BaseMeshCoderTest, CoincidentVerticesAreToldApartByTheirTriangles) {
  // Two vertices closer than a quantisation step (as a contour makes them): Draco decodes
  // both at one position; their triangles tell which is which, so edgebreaker is kept.
  const TriangleMesh mesh = testing::SphereMesh(4);
  TriangleMesh twins = mesh;
  twins.positions[1] = twins.positions[0] + Eigen::Vector3f(1e-7f, 0, 0);
  // And a sliver on its own whose three corners share one quantised position: nothing tells
  // them apart, and nothing needs to (any assignment decodes the same).
  const std::uint32_t first = static_cast<std::uint32_t>(twins.positions.size());
  for (int c = 0; c < 3; ++c) {
    twins.positions.push_back(Eigen::Vector3f(0.1f, 0.2f, 0.3f) + Eigen::Vector3f(0, 1e-7f * c, 0));
  }
  twins.triangles.push_back(Triangle(first, first + 1, first + 2));
  auto sequential_settings = BaseMeshEncoding{};
  sequential_settings.try_edgebreaker = false;
  auto sequential = EncodeBaseMesh(twins, sequential_settings);
  auto small = EncodeBaseMesh(twins);
  ASSERT_TRUE(small.ok() && sequential.ok());
  EXPECT_LT(small->bytes.size(), sequential->bytes.size() / 2);
  ExpectMappedBack(twins, *small, 2.0f / ((1 << 16) - 1));
}

TEST(BaseMeshCoderTest, VerticesOneStepCannotPartGetAFinerStepNotTheSequentialCoder) {
  // At 3 bits a 1026-vertex sphere puts several vertices in each quantisation cell, and
  // nothing tells them all apart: edgebreaker is tried one bit finer, where they part.
  const TriangleMesh sphere = testing::SphereMesh(4);
  BaseMeshEncoding coarse;
  coarse.position_bits = 3;
  BaseMeshEncoding sequential_settings = coarse;
  sequential_settings.try_edgebreaker = false;
  auto sequential = EncodeBaseMesh(sphere, sequential_settings);
  auto small = EncodeBaseMesh(sphere, coarse);
  ASSERT_TRUE(small.ok() && sequential.ok());
  EXPECT_EQ(sequential->position_bits, 3);
  ASSERT_GT(small->position_bits, 3);
  EXPECT_LE(small->position_bits, 3 + kEdgebreakerExtraBits);
  EXPECT_LT(small->bytes.size(), sequential->bytes.size() / 2);
  const float size = BoundingBox(sphere).sizes().maxCoeff();
  ExpectMappedBack(sphere, *small, size / float((1 << small->position_bits) - 1));
  // Where one step parts every vertex, the asked quantisation is kept.
  BaseMeshEncoding fine;
  fine.position_bits = 10;
  auto kept = EncodeBaseMesh(sphere, fine);
  ASSERT_TRUE(kept.ok());
  EXPECT_EQ(kept->position_bits, 10);
  EXPECT_FALSE(kept->vertex_in_decoded.empty());
}

TEST(BaseMeshCoderTest, DamagedStreamsFailCleanly) {
  auto encoded = EncodeBaseMesh(testing::MakeGridPlane(1.0f, 8));
  ASSERT_TRUE(encoded.ok());
  const std::vector<std::uint8_t>& bytes = encoded->bytes;
  for (std::size_t cut = 0; cut < bytes.size(); cut += 7) {
    auto decoded = DecodeBaseMesh(std::span(bytes.data(), cut));
    if (decoded.ok()) {
      EXPECT_TRUE(ValidateMesh(*decoded, "cut").ok());
    } else {
      EXPECT_EQ(decoded.status().code(), StatusCode::kCorrupt);
    }
  }
  EXPECT_EQ(DecodeBaseMesh({}).status().code(), StatusCode::kCorrupt);
}

TEST(BaseMeshCoderTest, ForgedCountsAndOtherDracoVersionsAreRefusedBeforeDracoAllocates) {
  // A grid that sits on the 8-bit lattice codes 130k triangles in under 400 bytes, so no
  // bound on triangles per byte is safe; the cap is on the count itself. (Every one of its
  // vertices has several candidates within a quantisation step: the encoder's search for
  // Draco's order once recursed once per vertex here and overflowed the stack.)
  BaseMeshEncoding settings;
  settings.position_bits = 8;
  const TriangleMesh grid = testing::MakeGridPlane(1.0f, 255);
  auto encoded = EncodeBaseMesh(grid, settings);
  ASSERT_TRUE(encoded.ok()) << encoded.status().message();
  EXPECT_EQ(encoded->decoded.triangle_count(), grid.triangle_count());
  EXPECT_LT(encoded->bytes.size(), 400u);

  // Edgebreaker stream declaring 2^28 triangles.
  std::vector<std::uint8_t> forged = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 1, 0, 0, 0,
                                      0x10, 0x80, 0x80, 0x80, 0x80, 0x01};
  forged.resize(24, 0);
  auto decoded = DecodeBaseMesh(forged);
  ASSERT_FALSE(decoded.ok());
  EXPECT_EQ(decoded.status().code(), StatusCode::kCorrupt);
  EXPECT_NE(decoded.status().message().find("268435456 triangles"), std::string::npos)
      << decoded.status().message();
  // The same bytes as bitstream 1.1: the fuzzed stream that asked Draco for 4.4 GB was one.
  forged[5] = 1;
  forged[6] = 1;
  EXPECT_NE(DecodeBaseMesh(forged).status().message().find("version 1.1"), std::string::npos);
  // A point cloud, and a mesh with metadata.
  forged = encoded->bytes;
  forged[7] = 0;
  EXPECT_NE(DecodeBaseMesh(forged).status().message().find("not a mesh"), std::string::npos);
  forged = encoded->bytes;
  forged[10] |= 0x80;
  EXPECT_NE(DecodeBaseMesh(forged).status().message().find("metadata"), std::string::npos);
}

TEST(BaseMeshCoderTest, RejectsInvalidSettingsAndMeshes) {
  BaseMeshEncoding settings;
  settings.position_bits = 0;
  EXPECT_EQ(EncodeBaseMesh(testing::MakeGridPlane(1.0f, 2), settings).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_FALSE(EncodeBaseMesh(TriangleMesh{}).ok());
}

}  // namespace
}  // namespace meshvid
