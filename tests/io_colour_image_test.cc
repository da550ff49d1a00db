// Colour PNGs beside depth images: file round trip, the manifest's colour_frames and
// colour_pattern, per-vertex colour of the meshed views, and bad colour input.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
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

/// A flat depth image (1.25 m at 0.5 mm a unit) with a hole in its top-left pixel.
DepthImage FlatDepth() {
  DepthImage image{kWidth, kHeight, std::vector<std::uint16_t>(kWidth * kHeight, 2500)};
  image.values[0] = 0;
  return image;
}

/// Pixel (u, v)'s colour in the test images: a ramp in red and green, blue the frame.
Colour PixelColour(int u, int v, int frame) {
  return Colour(static_cast<std::uint8_t>(u * 6), static_cast<std::uint8_t>(v * 8),
                static_cast<std::uint8_t>(100 + frame));
}

ColourImage RampImage(int frame, int width = kWidth, int height = kHeight) {
  ColourImage image{width, height, {}};
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) image.pixels.push_back(PixelColour(u, v, frame));
  }
  return image;
}

/// A manifest of one view of 40 x 30 pixels (fx = fy = 50, centre 19.5, 14.5), depth scale
/// 0.0005, and the given frames and colour fields.
std::string ColourManifest(const std::string& files) {
  return R"({"format": "meshvid-capture", "version": 1,
      "views": [{"intrinsics": {"width": 40, "height": 30, "fx": 50, "fy": 50, "cx": 19.5,
      "cy": 14.5}, "depth_scale": 0.0005}], )" +
         files + "}";
}

/// Expects every vertex of `mesh` (a FlatDepth view at the origin) to have the colour of the
/// pixel it was back-projected from.
void ExpectPixelColours(const TriangleMesh& mesh, int frame) {
  ASSERT_EQ(mesh.colours.size(), mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Eigen::Vector3f& p = mesh.positions[i];
    const int u = static_cast<int>(std::lround(p.x() / p.z() * 50 + 19.5));
    const int v = static_cast<int>(std::lround(p.y() / p.z() * 50 + 14.5));
    ASSERT_EQ(mesh.colours[i], PixelColour(u, v, frame)) << "vertex " << i;
  }
}

TEST(ColourPngTest, RoundTripsAndReadsGreyAsRgb) {
  TempDir dir;
  const ColourImage image = RampImage(3, 7, 5);
  ASSERT_TRUE(WriteColourPng(dir.File("c.png"), image).ok());
  auto read = ReadColourPng(dir.File("c.png"));
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->width, 7);
  EXPECT_EQ(read->height, 5);
  EXPECT_EQ(read->pixels, image.pixels);
  // A 16-bit greyscale PNG (a depth image) reads as grey, its high byte in every channel.
  DepthImage grey{2, 1, {0x1234, 0xff00}};
  ASSERT_TRUE(WriteDepthPng(dir.File("g.png"), grey).ok());
  read = ReadColourPng(dir.File("g.png"));
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->pixels,
            (std::vector<Colour>{Colour(0x12, 0x12, 0x12), Colour(0xff, 0xff, 0xff)}));
  // A uniform grey image's file is smaller than a 1100th (deflate's limit) of its pixels
  // expanded to RGB; the reader bounds the file by its rows as stored, so it is read.
  DepthImage uniform{4000, 4000, std::vector<std::uint16_t>(4000 * 4000, 0x4000)};
  ASSERT_TRUE(WriteDepthPng(dir.File("u.png"), uniform).ok());
  const auto uniform_size = std::filesystem::file_size(dir.File("u.png"));
  EXPECT_LT(uniform_size, 4000u * 4000u * 3u / 1100u);
  read = ReadColourPng(dir.File("u.png"));
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->pixels[123456], Colour(0x40, 0x40, 0x40));
  EXPECT_EQ(ReadColourPng(dir.File("none.png")).status().code(), StatusCode::kNotFound);
  WriteFile(dir.File("text.png"), "not a png");
  EXPECT_EQ(ReadColourPng(dir.File("text.png")).status().message(),
            dir.File("text.png") + ": not a PNG file");
}

TEST(ColourPngTest, DepthViewsTakeTheirPixelsColours) {
  TempDir dir;
  for (int f = 0; f < 2; ++f) {
    ASSERT_TRUE(WriteDepthPng(dir.File("d" + std::to_string(f) + ".png"), FlatDepth()).ok());
    ASSERT_TRUE(WriteColourPng(dir.File("c" + std::to_string(f) + ".png"), RampImage(f)).ok());
  }
  // The frames form.
  WriteFile(dir.File("m.json"), ColourManifest(R"("frames": [["d0.png"], ["d1.png"]],
      "colour_frames": [["c0.png"], ["c1.png"]])"));
  auto capture = CaptureSequence::Open(dir.File("m.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  EXPECT_TRUE((*capture)->has_colour_images());
  EXPECT_EQ((*capture)->colour_path(1, 0), dir.File("c1.png"));
  for (int f = 0; f < 2; ++f) {
    const auto mesh = (*capture)->LoadView(f, 0);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    EXPECT_EQ(mesh->vertex_count(), std::size_t(kWidth * kHeight - 1));
    ExpectPixelColours(*mesh, f);
  }
  // The pattern form, from its first frame.
  WriteFile(dir.File("p.json"), ColourManifest(R"("pattern": "d{frame}.png", "frame_count": 1,
      "first_frame": 1, "colour_pattern": "c{frame}.png")"));
  capture = CaptureSequence::Open(dir.File("p.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  const auto mesh = (*capture)->LoadView(0, 0);
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  ExpectPixelColours(*mesh, 1);
  // Written back, a manifest keeps its colour images (null for a view without one).
  CaptureInfo info = (*capture)->info();
  ASSERT_TRUE(
      WriteCaptureManifest(dir.File("w.json"), info, {{"d0.png"}, {"d1.png"}}, {{"c0.png"}, {""}})
          .ok());
  EXPECT_NE(testing::ReadFile(dir.File("w.json")).find("null"), std::string::npos);
  capture = CaptureSequence::Open(dir.File("w.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  EXPECT_EQ((*capture)->colour_path(1, 0), "");
  const auto uncoloured = (*capture)->LoadView(1, 0);
  ASSERT_TRUE(uncoloured.ok()) << uncoloured.status().ToString();
  EXPECT_TRUE(uncoloured->colours.empty());
  // A capture without colour images has none, nor one whose colour images are all null.
  WriteFile(dir.File("n.json"), ColourManifest(R"("frames": [["d0.png"]])"));
  capture = CaptureSequence::Open(dir.File("n.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  EXPECT_FALSE((*capture)->has_colour_images());
  WriteFile(dir.File("n.json"), ColourManifest(R"("frames": [["d0.png"]],
      "colour_frames": [[null]])"));
  capture = CaptureSequence::Open(dir.File("n.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  EXPECT_FALSE((*capture)->has_colour_images());
}

TEST(ColourPngTest, BadColourInputIsReportedWithTheFile) {
  TempDir dir;
  ASSERT_TRUE(WriteDepthPng(dir.File("d0.png"), FlatDepth()).ok());
  ASSERT_TRUE(WriteColourPng(dir.File("small.png"), RampImage(0, 20, 30)).ok());
  WriteFile(dir.File("m.json"), ColourManifest(R"("frames": [["d0.png"]],
      "colour_frames": [["small.png"]])"));
  auto capture = CaptureSequence::Open(dir.File("m.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  const auto wrong_size = (*capture)->LoadView(0, 0);
  ASSERT_FALSE(wrong_size.ok());
  EXPECT_EQ(wrong_size.status().message(),
            dir.File("small.png") + ": colour image is 20 x 30 pixels but its depth image " +
                dir.File("d0.png") + " is 40 x 30");

  // A missing colour image is found when the capture is opened.
  WriteFile(dir.File("m.json"), ColourManifest(R"("frames": [["d0.png"]],
      "colour_frames": [["gone.png"]])"));
  capture = CaptureSequence::Open(dir.File("m.json"));
  ASSERT_FALSE(capture.ok());
  EXPECT_NE(capture.status().message().find("1 of the 2 view files are missing, the first is " +
                                            dir.File("gone.png") +
                                            " (frame 0, view 0, its colour image)"),
            std::string::npos)
      << capture.status().message();

  // Shapes and kinds the manifest refuses.
  const std::pair<const char*, const char*> bad[] = {
      {R"("frames": [["d0.png"]], "colour_frames": [["c.png"], ["c.png"]])",
       "colour_frames must be an array of per-frame colour image lists, one for each of the 1"},
      {R"("frames": [["d0.png"]], "colour_frames": [[7]])",
       "colour_frames[0][0] must be a file name or null"},
      {R"("frames": [["d0.png"]], "colour_pattern": "c{frame}.png")",
       "colour_pattern goes with pattern"},
      {R"("frames": [["d0.png"]], "colour_frame": [["c.png"]])",
       "colour_frame is not a known field"},
      {R"("pattern": "d{frame}.png", "frame_count": 1, "colour_frames": [["c.png"]])",
       "colour_frames goes with frames; with pattern, give colour_pattern"},
      {R"("pattern": "d{frame}.png", "frame_count": 1, "colour_pattern": "c{frame")",
       "colour_pattern is invalid"},
  };
  for (const auto& [files, problem] : bad) {
    WriteFile(dir.File("m.json"), ColourManifest(files));
    capture = CaptureSequence::Open(dir.File("m.json"));
    ASSERT_FALSE(capture.ok()) << files;
    EXPECT_NE(capture.status().message().find(problem), std::string::npos)
        << capture.status().message();
  }
  // A colour image goes with a depth image only: a mesh carries its own colours.
  WriteFile(dir.File("v.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
            "property float y\nproperty float z\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  WriteFile(dir.File("m.json"), ColourManifest(R"("frames": [["v.ply"]],
      "colour_frames": [["small.png"]])"));
  capture = CaptureSequence::Open(dir.File("m.json"));
  ASSERT_FALSE(capture.ok());
  EXPECT_NE(capture.status().message().find("which is not a PNG depth image"), std::string::npos)
      << capture.status().message();
}

}  // namespace
}  // namespace meshvid
