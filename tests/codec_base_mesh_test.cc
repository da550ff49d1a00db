// Tests of the Draco base-mesh coder.
#include <gtest/gtest.h>

#include "codec/dec/base_mesh_decoder.h"
#include "codec/enc/base_mesh_encoder.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

TEST(BaseMeshCoderTest, RoundTripKeepsTheMeshWithinQuantisation) {
  const TriangleMesh mesh = testing::MakeGridPlane(2.0f, 20, 0.5f);
  BaseMeshEncoding settings;
  settings.position_bits = 14;
  settings.preserve_order = false;  // edgebreaker
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

TEST(BaseMeshCoderTest, SequentialCodingKeepsVertexAndTriangleOrder) {
  const TriangleMesh mesh = testing::MakeGridPlane(2.0f, 20, 0.5f);
  auto encoded = EncodeBaseMesh(mesh);  // preserve_order is the default
  ASSERT_TRUE(encoded.ok());
  ASSERT_EQ(encoded->decoded.vertex_count(), mesh.vertex_count());
  EXPECT_EQ(encoded->decoded.triangles, mesh.triangles);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_LE((encoded->decoded.positions[v] - mesh.positions[v]).cwiseAbs().maxCoeff(),
              2.0f / (1 << 16));
  }
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

TEST(BaseMeshCoderTest, RejectsInvalidSettingsAndMeshes) {
  BaseMeshEncoding settings;
  settings.position_bits = 0;
  EXPECT_EQ(EncodeBaseMesh(testing::MakeGridPlane(1.0f, 2), settings).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_FALSE(EncodeBaseMesh(TriangleMesh{}).ok());
}

}  // namespace
}  // namespace meshvid
