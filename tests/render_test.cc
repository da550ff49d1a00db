// meshvid render's library: camera framing, shading, error colours, PNG and MP4 output.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include "tests/test_util.h"
#include "tools/render/camera.h"
#include "tools/render/error_colours.h"
#include "tools/render/mp4_writer.h"
#include "tools/render/render_job.h"
#include "tools/render/rgb_image.h"
#include "tools/render/surface_renderer.h"

namespace meshvid {
namespace {

/// A closed box with corners `lo` and `hi` (12 triangles).
TriangleMesh Box(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.positions.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(),
                                i & 4 ? hi.z() : lo.z());
  }
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.emplace_back(f[0], f[1], f[2]);
    mesh.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return mesh;
}

bool IsBackground(const RgbImage& image, int x, int y) {
  const Rgb expected = BackgroundColour(y, image.height);
  const std::uint8_t* p = image.at(x, y);
  return p[0] == expected[0] && p[1] == expected[1] && p[2] == expected[2];
}

TEST(RenderCameraTest, DefaultCameraFramesTheSubject) {
  const TriangleMesh box = Box({-0.2f, 0.0f, -0.1f}, {0.2f, 1.8f, 0.1f});  // a standing figure
  const RenderCamera camera = FrameBounds(BoundingBox(box), OrbitSpec{}, 160, 120);
  SurfaceRenderer renderer;
  ASSERT_TRUE(renderer.SetMesh(box).ok());
  const RgbImage image = renderer.Render(camera);
  EXPECT_FALSE(IsBackground(image, 80, 60));  // the centre shows the subject
  int top = image.height, bottom = -1;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (x == 0 || y == 0 || x == image.width - 1 || y == image.height - 1) {
        EXPECT_TRUE(IsBackground(image, x, y)) << "border pixel " << x << "," << y;
      }
      if (!IsBackground(image, x, y)) top = std::min(top, y), bottom = std::max(bottom, y);
    }
  }
  EXPECT_GT(bottom - top, image.height / 2);  // and fills most of the height
}

TEST(RenderCameraTest, ParsesOrbitSpecs) {
  auto spec = ParseOrbitSpec("90,-10,2");
  ASSERT_TRUE(spec.ok());
  EXPECT_EQ(spec->azimuth_degrees, 90);
  EXPECT_EQ(spec->elevation_degrees, -10);
  EXPECT_EQ(spec->zoom, 2);
  EXPECT_FALSE(ParseOrbitSpec("90").ok());
  EXPECT_FALSE(ParseOrbitSpec("a,b").ok());
  EXPECT_FALSE(ParseOrbitSpec("0,95").ok());
  // Azimuth 90 looks from +x: the camera sits on the +x side.
  const RenderCamera camera = FrameBounds(Eigen::AlignedBox3f(Eigen::Vector3f(-1, -1, -1),
                                                              Eigen::Vector3f(1, 1, 1)),
                                          {90, 0, 1}, 64, 64);
  EXPECT_GT(camera.eye.x(), 1.0f);
  EXPECT_NEAR(camera.forward.x(), -1.0f, 1e-5f);
}

TEST(RenderErrorTest, DistancesAndColours) {
  const TriangleMesh truth = testing::MakeGridPlane(1.0f, 4);
  const TriangleMesh off = testing::MakeGridPlane(1.0f, 4, 0.002f);  // 2 mm above
  auto reference = SurfaceDistance::Build(truth);
  ASSERT_TRUE(reference.ok());
  const std::vector<float> distances = VertexDistances(off, **reference);
  for (float d : distances) EXPECT_NEAR(d, 0.002f, 1e-6f);
  const auto colours = ErrorColours(distances, 0.004f);
  EXPECT_TRUE(colours[0].isApprox(ErrorColour(0.5f)));
  EXPECT_TRUE(ErrorColour(-1).isApprox(ErrorColour(0)));
  EXPECT_TRUE(ErrorColour(7).isApprox(ErrorColour(1)));
  EXPECT_GT(ErrorColour(1).x(), ErrorColour(1).z());  // red at the top
  EXPECT_LT(ErrorColour(0).x(), ErrorColour(0).z());  // blue at the bottom
  EXPECT_EQ(RoundUpNicely(3.2f), 5.0f);
  EXPECT_EQ(RoundUpNicely(0.011f), 0.02f);
  EXPECT_EQ(RoundUpNicely(2.0f), 2.0f);
}

TEST(RenderImageTest, TextPanelsAndPng) {
  RgbImage a(20, 10, {255, 0, 0}), b(30, 10, {0, 0, 255});
  EXPECT_EQ(DrawText(&a, 1, 1, "0.5 MM", {255, 255, 255}, 1), TextWidth("0.5 MM", 1));
  const RgbImage both = SideBySide({a, b});
  EXPECT_EQ(both.width, 50);
  EXPECT_EQ(both.at(25, 5)[2], 255);
  auto png = EncodePng(both);
  ASSERT_TRUE(png.ok());
  EXPECT_EQ(png->substr(1, 3), "PNG");
  EXPECT_FALSE(EncodePng(RgbImage()).ok());
}

TEST(RenderMp4Test, WritesAPlayableH264OrHevcFile) {
  testing::TempDir dir;
  const std::string path = dir.File("v/out.mp4");
  auto writer = Mp4Writer::Create(path, 64, 48, 25.0);
  ASSERT_TRUE(writer.ok()) << writer.status().message();
  EXPECT_FALSE(Mp4Writer::Create(dir.File("odd.mp4"), 63, 48, 25.0).ok());
  for (int i = 0; i < 10; ++i) {
    ASSERT_TRUE((*writer)->AddFrame(RgbImage(64, 48, {static_cast<std::uint8_t>(20 * i), 128, 60})).ok());
  }
  ASSERT_TRUE((*writer)->Finish().ok());
  // Read it back with libavformat: one video stream of the right codec, size and length.
  AVFormatContext* format = nullptr;
  ASSERT_EQ(avformat_open_input(&format, path.c_str(), nullptr, nullptr), 0);
  ASSERT_GE(avformat_find_stream_info(format, nullptr), 0);
  ASSERT_EQ(format->nb_streams, 1u);
  const AVCodecParameters* par = format->streams[0]->codecpar;
  EXPECT_TRUE(par->codec_id == AV_CODEC_ID_H264 || par->codec_id == AV_CODEC_ID_HEVC);
  EXPECT_EQ(par->width, 64);
  EXPECT_EQ(par->height, 48);
  EXPECT_EQ(par->format, AV_PIX_FMT_YUV420P);
  AVPacket* packet = av_packet_alloc();
  int packets = 0;
  while (av_read_frame(format, packet) >= 0) {
    ++packets;
    av_packet_unref(packet);
  }
  EXPECT_EQ(packets, 10);
  av_packet_free(&packet);
  avformat_close_input(&format);
}

TEST(RenderJobTest, PanelsSideBySideAndBadRanges) {
  testing::TempDir dir;
  RenderJobOptions options;
  options.inputs = {"scene:arm-block", "scene:arm-block"};
  options.error_against = "scene:cloth";  // any surface: colours the panels
  options.output = dir.File("f{frame:02}.png");
  options.first_frame = 2;
  options.end_frame = 4;
  options.width = 96;
  options.height = 64;
  auto stats = RunRenderJob(options);
  ASSERT_TRUE(stats.ok()) << stats.status().message();
  EXPECT_EQ(stats->frames, 2);
  EXPECT_EQ(stats->width, 192);
  EXPECT_GT(stats->error_max_mm, 0);
  EXPECT_FALSE(testing::ReadFile(dir.File("f03.png")).empty());
  // Frames past the end are clipped, and said so; a range starting past it fails.
  options.first_frame = 3;
  options.end_frame = 100000;
  stats = RunRenderJob(options);
  ASSERT_TRUE(stats.ok()) << stats.status().message();
  EXPECT_EQ(stats->clipped_frames.find("frames 3:100000 run past the "), 0u)
      << stats->clipped_frames;
  EXPECT_LT(stats->frames, 100000 - 3);
  options.first_frame = 100000;
  EXPECT_FALSE(RunRenderJob(options).ok());
  options.output = dir.File("x.gif");
  EXPECT_FALSE(RunRenderJob(options).ok());
  EXPECT_EQ(PanelLabel("cap/manifest.json", -1), "input views");
  EXPECT_EQ(PanelLabel("out/samba.mvid", 2), "samba.mvid L2");
  EXPECT_EQ(PanelLabel("gt/samba.obj", -1), "ground truth samba");
  EXPECT_EQ(PanelLabel("cap/ground_truth.obj", -1), "ground truth");
}

}  // namespace
}  // namespace meshvid
