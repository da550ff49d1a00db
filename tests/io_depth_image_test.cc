// Tests of 16-bit PNG depth images: file round trip, meshing, and capture input.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tests/test_util.h"
#include "tools/io/capture.h"
#include "tools/io/depth_image.h"

namespace meshvid {
namespace {

using testing::TempDir;
using testing::WriteFile;

constexpr int kWidth = 40;
constexpr int kHeight = 30;

PinholeIntrinsics TestIntrinsics() {
  return PinholeIntrinsics{kWidth, kHeight, 50, 50, 19.5, 14.5};
}

/// A kWidth x kHeight image whose left `split` columns hold `left` and the rest `right`.
DepthImage TwoLevelImage(std::uint16_t left, std::uint16_t right, int split) {
  DepthImage image{kWidth, kHeight, {}};
  for (int v = 0; v < kHeight; ++v) {
    for (int u = 0; u < kWidth; ++u) image.values.push_back(u < split ? left : right);
  }
  return image;
}

/// A manifest of one view with TestIntrinsics(), depth_scale 0.0005, and `extra` view fields.
std::string DepthManifest(const std::string& file, const std::string& extra = "") {
  return R"({"format": "meshvid-capture", "version": 1, "depth_jump_ratio": 0.03,
      "views": [{"intrinsics": {"width": 40, "height": 30, "fx": 50, "fy": 50, "cx": 19.5,
      "cy": 14.5}, "depth_scale": 0.0005)" +
         extra + R"(}], "frames": [[")" + file + R"("]]})";
}

TEST(DepthPngTest, RoundTripsEveryValueExactly) {
  TempDir dir;
  DepthImage image{7, 5, {}};
  for (int i = 0; i < 35; ++i) image.values.push_back(static_cast<std::uint16_t>(i * 1927 % 65536));
  image.values[3] = 0;
  image.values[4] = 65535;
  image.values[5] = 256;
  ASSERT_TRUE(WriteDepthPng(dir.File("d.png"), image).ok());
  const StatusOr<DepthImage> read = ReadDepthPng(dir.File("d.png"));
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->width, 7);
  EXPECT_EQ(read->height, 5);
  EXPECT_EQ(read->values, image.values);
}

TEST(DepthPngTest, BadFilesAreReportedWithTheirName) {
  TempDir dir;
  EXPECT_EQ(ReadDepthPng(dir.File("none.png")).status().code(), StatusCode::kNotFound);
  WriteFile(dir.File("text.png"), "not a png at all");
  EXPECT_EQ(ReadDepthPng(dir.File("text.png")).status().message(),
            dir.File("text.png") + ": not a PNG file");
  ASSERT_TRUE(WriteDepthPng(dir.File("cut.png"), TwoLevelImage(1, 2, 5)).ok());
  const std::string png = testing::ReadFile(dir.File("cut.png"));
  WriteFile(dir.File("cut.png"), png.substr(0, png.size() / 2));
  const auto cut = ReadDepthPng(dir.File("cut.png"));
  ASSERT_FALSE(cut.ok());
  EXPECT_EQ(cut.status().code(), StatusCode::kCorrupt);
  EXPECT_EQ(cut.status().message().rfind(dir.File("cut.png") + ": damaged PNG", 0), 0u)
      << cut.status().message();
  EXPECT_EQ(WriteDepthPng(dir.File("x.png"), DepthImage{3, 3, {1, 2}}).code(),
            StatusCode::kInvalidArgument);
}

/// PNG's CRC-32 (ISO 3309) of `bytes`.
std::uint32_t PngCrc(std::string_view bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (const char c : bytes) {
    crc ^= static_cast<std::uint8_t>(c);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1)));
  }
  return ~crc;
}

TEST(DepthPngTest, AHeaderClaimingMorePixelsThanTheFileHoldsFailsBeforeAllocating) {
  // A real 40 x 30 image whose IHDR now says 1000000 x 1000000 (2 TB of 16-bit samples),
  // its CRC recomputed: refused from the file size, not by a failed allocation.
  TempDir dir;
  ASSERT_TRUE(WriteDepthPng(dir.File("d.png"), TwoLevelImage(1, 2, 5)).ok());
  std::string png = testing::ReadFile(dir.File("d.png"));
  ASSERT_EQ(png.substr(12, 4), "IHDR");
  for (const int at : {16, 20}) {  // width, height: big-endian u32
    const std::uint32_t million = 1000000;
    for (int i = 0; i < 4; ++i) png[at + i] = static_cast<char>(million >> (24 - 8 * i));
  }
  const std::uint32_t crc = PngCrc(std::string_view(png).substr(12, 17));
  for (int i = 0; i < 4; ++i) png[29 + i] = static_cast<char>(crc >> (24 - 8 * i));
  WriteFile(dir.File("huge.png"), png);
  const auto huge = ReadDepthPng(dir.File("huge.png"));
  EXPECT_EQ(huge.status().ToString(),
            "corrupt: " + dir.File("huge.png") + ": a 1000000 x 1000000 image needs " +
                "2000000000000 bytes, more than the " + std::to_string(png.size()) +
                "-byte file can hold (damaged header?)");
}

TEST(DepthMeshTest, PlaneThroughCaptureHasExactSizeAndDepth) {
  TempDir dir;
  // 1.25 m at 0.5 mm per unit.
  ASSERT_TRUE(WriteDepthPng(dir.File("plane.png"), TwoLevelImage(2500, 2500, 0)).ok());
  WriteFile(dir.File("manifest.json"), DepthManifest("plane.png"));
  const auto capture = CaptureSequence::Open(dir.File("manifest.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  const auto mesh = (*capture)->LoadView(0, 0);
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->vertex_count(), static_cast<size_t>(kWidth * kHeight));
  EXPECT_EQ(mesh->triangle_count(), static_cast<size_t>(2 * (kWidth - 1) * (kHeight - 1)));
  for (const Eigen::Vector3f& p : mesh->positions) EXPECT_NEAR(p.z(), 1.25f, 1e-5f);
  // z-depth, not ray length: the corner pixel (0, 0) is at x = (0 - cx) / fx * z.
  const Eigen::AlignedBox3f box = BoundingBox(*mesh);
  EXPECT_NEAR(box.min().x(), -19.5 / 50 * 1.25, 1e-6);
  EXPECT_NEAR(box.max().x(), 19.5 / 50 * 1.25, 1e-6);
  EXPECT_NEAR(box.min().y(), -14.5 / 50 * 1.25, 1e-6);
  // Triangles face the sensor at the origin.
  for (size_t t = 0; t < mesh->triangle_count(); ++t) {
    const Eigen::Vector3f to_sensor = -mesh->positions[mesh->triangles[t][0]];
    ASSERT_GT(TriangleNormal(*mesh, t).dot(to_sensor), 0.0f) << "triangle " << t;
  }
}

TEST(DepthMeshTest, ExtrinsicsMoveDepthImagesToTheWorld) {
  TempDir dir;
  ASSERT_TRUE(WriteDepthPng(dir.File("plane.png"), TwoLevelImage(2000, 2000, 0)).ok());
  // The camera sits at (0, 0, 3) looking back along -z (a half turn about y).
  WriteFile(dir.File("manifest.json"),
            DepthManifest("plane.png",
                          R"(, "world_from_camera": [-1,0,0,0, 0,1,0,0, 0,0,-1,3, 0,0,0,1])"));
  const auto capture = CaptureSequence::Open(dir.File("manifest.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  const auto mesh = (*capture)->LoadView(0, 0);
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->vertex_count(), static_cast<size_t>(kWidth * kHeight));
  for (const Eigen::Vector3f& p : mesh->positions) EXPECT_NEAR(p.z(), 2.0f, 1e-5f);
}

TEST(DepthMeshTest, DepthJumpSplitsTheMesh) {
  const DepthImage image = TwoLevelImage(2000, 4000, 20);  // 1 m left, 2 m right
  const auto mesh = MeshDepthImage(image, TestIntrinsics(), 0.0005, Eigen::Isometry3d::Identity(),
                                   RangeGridMeshing{0.03f}, "d");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->vertex_count(), static_cast<size_t>(kWidth * kHeight));
  // Each half keeps its 19 x 29 cells; the 29 cells across the jump are dropped.
  EXPECT_EQ(mesh->triangle_count(), static_cast<size_t>(2 * 2 * 19 * 29));
  for (const Triangle& t : mesh->triangles) {
    const float z0 = mesh->positions[t[0]].z();
    EXPECT_EQ(mesh->positions[t[1]].z(), z0);
    EXPECT_EQ(mesh->positions[t[2]].z(), z0);
  }
  // With a tolerant rule the two halves are joined.
  const auto joined = MeshDepthImage(image, TestIntrinsics(), 0.0005, Eigen::Isometry3d::Identity(),
                                     RangeGridMeshing{2.0f}, "d");
  ASSERT_TRUE(joined.ok());
  EXPECT_EQ(joined->triangle_count(), static_cast<size_t>(2 * 39 * 29));
}

TEST(DepthMeshTest, MisuseIsReported) {
  const auto empty = MeshDepthImage(TwoLevelImage(0, 0, 0), TestIntrinsics(), 0.001,
                                    Eigen::Isometry3d::Identity(), {}, "z.png");
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.status().message().rfind("z.png: depth image gives no triangle", 0), 0u);
  PinholeIntrinsics wrong = TestIntrinsics();
  wrong.width = 41;
  EXPECT_EQ(MeshDepthImage(TwoLevelImage(9, 9, 0), wrong, 0.001, Eigen::Isometry3d::Identity(), {},
                           "w.png")
                .status()
                .message(),
            "w.png: depth image is 40 x 30 pixels but its intrinsics say 41 x 30");

  // Depth images without intrinsics are refused when the capture is opened.
  TempDir dir;
  ASSERT_TRUE(WriteDepthPng(dir.File("d0_v0.png"), TwoLevelImage(9, 9, 0)).ok());
  const auto capture = CaptureSequence::Open(dir.File("d{frame}_v{view}.png"));
  ASSERT_FALSE(capture.ok());
  EXPECT_NE(capture.status().message().find("has depth images (" + dir.File("d0_v0.png") +
                                            ") but no intrinsics"),
            std::string::npos)
      << capture.status().message();
}

}  // namespace
}  // namespace meshvid
