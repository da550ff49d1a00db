// Tests of CaptureSequence (manifest, pattern, errors, extrinsics) and CaptureWindow.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <unordered_map>
#include <vector>

#include "tests/test_util.h"
#include "tools/io/capture.h"
#include "tools/io/capture_frame_source.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

using testing::MakeGridPlane;
using testing::TempDir;
using testing::WriteFile;

/// Writes a grid plane with `n` x `n` quads ((n+1)^2 vertices) to `path`.
void WritePlane(const std::string& path, int n, float z = 0.5f) {
  ASSERT_TRUE(WriteMesh(path, MakeGridPlane(2.0f, n, z)).ok()) << path;
}

/// A manifest of one view and one frame holding `file`.
std::string OneFileManifest(const std::string& file) {
  return R"({"format": "meshvid-capture", "version": 1, "views": [{"name": "v0"}],
             "frames": [[")" +
         file + R"("]]})";
}

StatusOr<std::unique_ptr<CaptureSequence>> OpenManifestText(const TempDir& dir,
                                                            const std::string& json) {
  WriteFile(dir.File("manifest.json"), json);
  return CaptureSequence::Open(dir.File("manifest.json"));
}

TEST(CaptureManifestTest, RoundTripsThroughWriteAndOpen) {
  TempDir dir;
  CaptureInfo info;
  info.frame_rate = 29.97;
  info.units = "mm";
  info.camera_coordinates = true;
  info.meshing.max_depth_jump_ratio = 0.05f;
  for (int v = 0; v < 2; ++v) {
    CaptureView view;
    view.name = "cam" + std::to_string(v);
    view.depth_scale = 0.00025;
    view.calibration.has_extrinsics = true;
    view.calibration.world_from_camera =
        Eigen::Translation3d(0.1 * v, -0.25, 1.5) *
        Eigen::AngleAxisd(0.3 + v, Eigen::Vector3d(1, 2, 3).normalized());
    info.views.push_back(view);
  }
  info.views[1].calibration.intrinsics = PinholeIntrinsics{640, 480, 525.5, 524.25, 319.5, 239.5};
  std::vector<std::vector<std::string>> paths;
  for (int f = 0; f < 3; ++f) {
    paths.emplace_back();
    for (int v = 0; v < 2; ++v) {
      const std::string name = "f" + std::to_string(f) + "_v" + std::to_string(v) + ".ply";
      WritePlane(dir.File(name), 2 + v);
      paths.back().push_back(name);
    }
  }
  ASSERT_TRUE(WriteCaptureManifest(dir.File("manifest.json"), info, paths).ok());
  const auto capture = CaptureSequence::Open(dir.File("manifest.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  const CaptureSequence& c = **capture;
  EXPECT_EQ(c.frame_count(), 3);
  EXPECT_EQ(c.view_count(), 2);
  EXPECT_EQ(c.info().frame_rate, 29.97);
  EXPECT_EQ(c.info().units, "mm");
  EXPECT_TRUE(c.info().camera_coordinates);
  EXPECT_EQ(c.info().meshing.max_depth_jump_ratio, 0.05f);
  for (int v = 0; v < 2; ++v) {
    const CaptureView& view = c.info().views[v];
    EXPECT_EQ(view.name, info.views[v].name);
    EXPECT_EQ(view.depth_scale, 0.00025);
    EXPECT_TRUE(view.calibration.has_extrinsics);
    EXPECT_TRUE(view.calibration.world_from_camera.matrix() ==
                info.views[v].calibration.world_from_camera.matrix());
  }
  EXPECT_FALSE(c.info().views[0].calibration.intrinsics.has_value());
  ASSERT_TRUE(c.info().views[1].calibration.intrinsics.has_value());
  const PinholeIntrinsics& k = *c.info().views[1].calibration.intrinsics;
  EXPECT_EQ(k.width, 640);
  EXPECT_EQ(k.height, 480);
  EXPECT_EQ(k.fx, 525.5);
  EXPECT_EQ(k.fy, 524.25);
  EXPECT_EQ(k.cx, 319.5);
  EXPECT_EQ(k.cy, 239.5);
  EXPECT_EQ(c.view_path(2, 1), dir.File("f2_v1.ply"));
  const auto frame = c.LoadFrame(2);
  ASSERT_TRUE(frame.ok()) << frame.status().ToString();
  ASSERT_EQ(frame->size(), 2u);
  EXPECT_EQ((*frame)[0].vertex_count(), 9u);
  EXPECT_EQ((*frame)[1].vertex_count(), 16u);
  // The encoder's source hands the calibration on (SeenFreeSpace uses view 1 only).
  const auto source = CaptureFrameSource::Open(dir.File("manifest.json"));
  ASSERT_TRUE(source.ok()) << source.status().ToString();
  const std::vector<ViewCalibration> cameras = (*source)->view_cameras();
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_FALSE(cameras[0].intrinsics.has_value());
  ASSERT_TRUE(cameras[1].intrinsics.has_value());
  EXPECT_EQ(cameras[1].intrinsics->fx, 525.5);
  EXPECT_TRUE(cameras[1].has_extrinsics);
  EXPECT_TRUE(cameras[1].world_from_camera.matrix() ==
              info.views[1].calibration.world_from_camera.matrix());
}

TEST(CaptureManifestTest, PatternFormExpandsFromFirstFrame) {
  TempDir dir;
  for (int f = 1; f <= 2; ++f) {
    for (int v = 0; v < 2; ++v)
      WritePlane(dir.File("f0" + std::to_string(f) + "_v" + std::to_string(v) + ".obj"), 1);
  }
  const auto capture = OpenManifestText(dir, R"({"format": "meshvid-capture", "version": 1,
      "frame_rate": 30, "views": [{}, {"name": "right"}], "pattern": "f{frame:02}_v{view}.obj",
      "frame_count": 2, "first_frame": 1, "source": {"anything": [1, 2]}})");
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  EXPECT_EQ((*capture)->frame_count(), 2);
  EXPECT_EQ((*capture)->info().frame_rate, 30.0);
  EXPECT_EQ((*capture)->info().views[0].name, "v0");
  EXPECT_EQ((*capture)->info().views[1].name, "right");
  EXPECT_EQ((*capture)->view_path(0, 0), dir.File("f01_v0.obj"));
  EXPECT_EQ((*capture)->view_path(1, 1), dir.File("f02_v1.obj"));
}

TEST(CaptureManifestTest, APatternFrameCountBeyondTheFilesFailsBeforeExpanding) {
  // 10^9 frames of a pattern with two files on disk: refused at once by the missing last
  // frame, not after expanding a billion paths.
  TempDir dir;
  WritePlane(dir.File("f1.obj"), 1);
  const auto start = std::chrono::steady_clock::now();
  const auto capture = OpenManifestText(dir, R"({"format": "meshvid-capture", "version": 1,
      "views": [{}], "pattern": "f{frame}.obj", "frame_count": 1000000000, "first_frame": 1})");
  ASSERT_FALSE(capture.ok());
  EXPECT_EQ(capture.status().message(),
            dir.File("manifest.json") + ": frame_count is 1000000000 but the last frame's view "
                                        "file " + dir.File("f1000000000.obj") +
                                        " does not exist");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
}

TEST(CaptureManifestTest, BadFieldsNameTheManifestAndJsonPath) {
  TempDir dir;
  WritePlane(dir.File("a.ply"), 1);
  const std::string m = dir.File("manifest.json");
  const std::string head = R"({"format": "meshvid-capture", "version": 1, )";
  const std::string views3 = R"("views": [{}, {}, {}], )";
  struct Case {
    std::string json;
    std::string message;
  };
  const std::vector<Case> cases = {
      {head + views3 + R"("frames": [["a.ply","a.ply","a.ply"], ["a.ply","a.ply"]]})",
       m + ": frames[1] has 2 views, expected 3"},
      {head + R"("views": [{}, {"intrinsics": {"width": 4, "height": 3, "fx": 0, "fy": 1,
          "cx": 1, "cy": 1}}], "frames": [["a.ply", "a.ply"]]})",
       m + ": views[1].intrinsics.fx must be > 0"},
      {head + R"("views": [{"intrinsics": {"width": 4, "height": 3, "fx": 1, "fy": 1,
          "cx": 1}}], "frames": [["a.ply"]]})",
       m + ": views[0].intrinsics.cy is missing"},
      {head + R"("views": [{"world_from_camera": [2,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}],
          "frames": [["a.ply"]]})",
       m + ": views[0].world_from_camera is not a rigid transform: its upper-left 3x3 must be "
           "a rotation"},
      {head + R"("views": [{"world_from_camera": [1,0,0]}], "frames": [["a.ply"]]})",
       m + ": views[0].world_from_camera must be an array of 16 numbers (a row-major 4x4 "
           "matrix)"},
      {head + R"("coordinates": "camera", "views": [{}], "frames": [["a.ply"]]})",
       m + ": views[0].world_from_camera is required when coordinates is \"camera\""},
      {head + R"("coordinates": "image", "views": [{}], "frames": [["a.ply"]]})",
       m + ": coordinates must be \"world\" or \"camera\""},
      {head + R"("frame_rte": 3, "views": [{}], "frames": [["a.ply"]]})",
       m + ": frame_rte is not a known field (known: format, version, frame_rate, units, "
           "coordinates, depth_jump_ratio, views, frames, pattern, frame_count, first_frame, "
           "colour_frames, colour_pattern, source)"},
      {head + R"("frame_rate": -1, "views": [{}], "frames": [["a.ply"]]})",
       m + ": frame_rate must be > 0"},
      // A rate the .mvid writer refuses is refused here, before any file is read.
      {head + R"("frame_rate": 1e308, "views": [{}], "frames": [["a.ply"]]})",
       m + ": frame_rate must be at most 1000 (frames per second)"},
      {head + R"("views": [], "frames": [["a.ply"]]})",
       m + ": views must be a non-empty array of view objects"},
      {head + R"("views": [{}]})",
       m + ": frames or pattern (with frame_count) must be given, and not both"},
      {head + R"("views": [{}, {}], "pattern": "f{frame}.ply", "frame_count": 2})",
       m + ": pattern has no {view} placeholder but the capture has 2 views"},
      {R"({"format": "other", "version": 1, "views": [{}], "frames": [["a.ply"]]})",
       m + ": format must be \"meshvid-capture\""},
      {R"({"format": "meshvid-capture", "version": 2, "views": [{}], "frames": [["a.ply"]]})",
       m + ": version 2 is not supported (this meshvid reads version 1)"},
      {"{\"format\": ", m + ": not valid JSON"},
  };
  for (const Case& c : cases) {
    const auto capture = OpenManifestText(dir, c.json);
    ASSERT_FALSE(capture.ok()) << c.json;
    EXPECT_EQ(capture.status().message(), c.message);
  }
}

TEST(CaptureManifestTest, MissingFilesAreReportedAtOpen) {
  TempDir dir;
  WritePlane(dir.File("a.ply"), 1);
  const auto capture = OpenManifestText(dir, R"({"format": "meshvid-capture", "version": 1,
      "views": [{}, {}, {}],
      "frames": [["a.ply", "a.ply", "a.ply"], ["b.ply", "a.ply", "c.ply"]]})");
  ASSERT_FALSE(capture.ok());
  EXPECT_EQ(capture.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(capture.status().message(), dir.File("manifest.json") +
                                            ": 2 of the 6 view files are missing, the first is " +
                                            dir.File("b.ply") + " (frame 1, view 0)");
}

TEST(CapturePatternTest, OpensContiguousFramesAndLoadsViews) {
  TempDir dir;
  for (int f = 3; f <= 5; ++f) {
    for (int v = 0; v < 3; ++v) {
      WritePlane(dir.File("f000" + std::to_string(f) + "_v" + std::to_string(v) + ".ply"), 1 + v);
    }
  }
  const auto capture = CaptureSequence::Open(dir.File("f{frame:04}_v{view}.ply"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  EXPECT_EQ((*capture)->frame_count(), 3);
  EXPECT_EQ((*capture)->view_count(), 3);
  EXPECT_EQ((*capture)->info().views[2].name, "v2");
  EXPECT_FALSE((*capture)->info().camera_coordinates);
  EXPECT_EQ((*capture)->view_path(0, 0), dir.File("f0003_v0.ply"));
  EXPECT_EQ((*capture)->view_path(2, 1), dir.File("f0005_v1.ply"));
  const auto frame = (*capture)->LoadFrame(1);
  ASSERT_TRUE(frame.ok()) << frame.status().ToString();
  ASSERT_EQ(frame->size(), 3u);
  for (int v = 0; v < 3; ++v)
    EXPECT_EQ((*frame)[v].vertex_count(), static_cast<size_t>((v + 2) * (v + 2)));
  EXPECT_EQ((*capture)->LoadView(3, 0).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ((*capture)->LoadView(0, 3).status().message(),
            "view 3 is out of range: the capture has 3 views");
  EXPECT_EQ((*capture)->LoadView(-1, 0).status().message(),
            "frame -1 is out of range: the capture has 3 frames");
}

TEST(CapturePatternTest, ViewCountDifferingBetweenFramesIsAnError) {
  TempDir dir;
  for (int f = 0; f < 3; ++f) {
    for (int v = 0; v < 3; ++v) {
      if (f == 1 && v == 1) continue;
      WritePlane(dir.File("f000" + std::to_string(f) + "_v" + std::to_string(v) + ".ply"), 1);
    }
  }
  const std::string pattern = dir.File("f{frame:04}_v{view}.ply");
  const auto capture = CaptureSequence::Open(pattern);
  ASSERT_FALSE(capture.ok());
  EXPECT_EQ(capture.status().message(), "capture pattern '" + pattern +
                                            "': view count differs between frames: frame 1 "
                                            "has views {0,2}, expected 3 views (missing " +
                                            dir.File("f0001_v1.ply") + ")");
}

TEST(CapturePatternTest, FrameGapIsAnError) {
  TempDir dir;
  for (int f : {0, 1, 3}) WritePlane(dir.File("s" + std::to_string(f) + ".ply"), 1);
  const std::string pattern = dir.File("s{frame}.ply");
  const auto capture = CaptureSequence::Open(pattern);
  ASSERT_FALSE(capture.ok());
  EXPECT_EQ(capture.status().message(), "capture pattern '" + pattern +
                                            "': frames must be contiguous from 0, but frame 2 "
                                            "is missing (no " +
                                            dir.File("s2.ply") + ")");
  EXPECT_EQ(CaptureSequence::Open(dir.File("none{frame}.ply")).status().code(),
            StatusCode::kNotFound);
}

// Broken view files: the error comes from LoadView and names the file.
TEST(CaptureErrorsTest, BadViewFilesNameTheFile) {
  TempDir dir;
  WriteFile(dir.File("nan.obj"), "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
  WriteFile(dir.File("index.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  WriteFile(dir.File("empty.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  WritePlane(dir.File("truncated.ply"), 4);
  const std::string full = testing::ReadFile(dir.File("truncated.ply"));
  WriteFile(dir.File("truncated.ply"), full.substr(0, full.size() - 10));
  for (const char* name : {"nan.obj", "index.obj", "empty.obj", "truncated.ply"}) {
    const auto capture = OpenManifestText(dir, OneFileManifest(name));
    ASSERT_TRUE(capture.ok()) << capture.status().ToString();
    const auto mesh = (*capture)->LoadView(0, 0);
    ASSERT_FALSE(mesh.ok()) << name;
    EXPECT_NE(mesh.status().message().find(dir.File(name)), std::string::npos)
        << mesh.status().message();
    EXPECT_FALSE((*capture)->LoadFrame(0).ok());
  }
}

TEST(CaptureCoordinatesTest, CameraCoordinatesAreMovedByTheExtrinsics) {
  TempDir dir;
  WritePlane(dir.File("a.ply"), 2, 0.5f);
  // A quarter turn about z, then a translation (1, 2, 3): (x, y, z) -> (1 - y, 2 + x, 3 + z).
  const std::string view = R"({"world_from_camera": [0,-1,0,1, 1,0,0,2, 0,0,1,3, 0,0,0,1]})";
  for (const char* coordinates : {"camera", "world"}) {
    const auto capture = OpenManifestText(
        dir, std::string(R"({"format": "meshvid-capture", "version": 1, "coordinates": ")") +
                 coordinates + R"(", "views": [)" + view + R"(], "frames": [["a.ply"]]})");
    ASSERT_TRUE(capture.ok()) << capture.status().ToString();
    const auto mesh = (*capture)->LoadView(0, 0);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    const TriangleMesh plane = MakeGridPlane(2.0f, 2, 0.5f);
    ASSERT_EQ(mesh->vertex_count(), plane.vertex_count());
    const bool camera = std::string(coordinates) == "camera";
    for (size_t i = 0; i < plane.vertex_count(); ++i) {
      const Eigen::Vector3f& p = plane.positions[i];
      const Eigen::Vector3f expected =
          camera ? Eigen::Vector3f(1 - p.y(), 2 + p.x(), 3 + p.z()) : p;
      EXPECT_EQ(mesh->positions[i], expected) << coordinates << " vertex " << i;
    }
  }
}

TEST(CaptureConfTest, StanfordConfPosesEachScan) {
  TempDir dir;
  WritePlane(dir.File("a.ply"), 1, 0.5f);
  WritePlane(dir.File("b.ply"), 1, 0.5f);
  const double h = std::sqrt(0.5);
  WriteFile(dir.File("scan.conf"),
            "camera 0 0 1 0 0 0 1\n\nbmesh a.ply 1 2 3 0 0 0 1\nbmesh b.ply 0 0 0 0 0 " +
                std::to_string(h) + " " + std::to_string(h) + "\n");
  const auto capture = CaptureSequence::Open(dir.File("scan.conf"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  EXPECT_EQ((*capture)->frame_count(), 1);
  ASSERT_EQ((*capture)->view_count(), 2);
  EXPECT_EQ((*capture)->info().views[0].name, "a");
  EXPECT_EQ((*capture)->info().views[1].name, "b");
  const auto a = (*capture)->LoadView(0, 0);
  const auto b = (*capture)->LoadView(0, 1);
  ASSERT_TRUE(a.ok() && b.ok());
  const TriangleMesh plane = MakeGridPlane(2.0f, 1, 0.5f);
  for (size_t i = 0; i < plane.vertex_count(); ++i) {
    const Eigen::Vector3f& p = plane.positions[i];
    EXPECT_EQ(a->positions[i], p + Eigen::Vector3f(1, 2, 3));
    // The conjugate of a quarter turn about z: (x, y) -> (y, -x).
    EXPECT_NEAR((b->positions[i] - Eigen::Vector3f(p.y(), -p.x(), p.z())).norm(), 0, 1e-5);
  }
  // The scans' poses move their cameras too, but a .conf gives no intrinsics: nothing for
  // the encoder's free-space test.
  EXPECT_NEAR(((*capture)->view_camera(0).world_from_camera.translation() -
               Eigen::Vector3d(1, 2, 3)).norm(), 0, 1e-12);
  CaptureFrameSource conf_source(CaptureSequence::Open(dir.File("scan.conf")).value());
  EXPECT_TRUE(conf_source.view_cameras().empty());
  WriteFile(dir.File("bad.conf"), "bmesh a.ply 0 0 0 0 0 0 1\nscan b.ply\n");
  EXPECT_EQ(CaptureSequence::Open(dir.File("bad.conf")).status().message(),
            dir.File("bad.conf") +
                ":2: unknown keyword 'scan' (expected 'camera' or 'bmesh "
                "FILE tx ty tz qi qj qk qr')");
  WriteFile(dir.File("missing.conf"), "bmesh a.ply 0 0 0 0 0 0 1\nbmesh zz.ply 0 0 0 0 0 0 1\n");
  EXPECT_EQ(CaptureSequence::Open(dir.File("missing.conf")).status().message(),
            dir.File("missing.conf") + ": 1 of the 2 view files are missing, the first is " +
                dir.File("zz.ply") + " (frame 0, view 1)");
}

TEST(CaptureWindowTest, NeverHoldsMoreThanCapacity) {
  TempDir dir;
  for (int f = 0; f < 5; ++f) WritePlane(dir.File("w" + std::to_string(f) + ".ply"), f + 1);
  const auto capture = CaptureSequence::Open(dir.File("w{frame}.ply"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  CaptureWindow window(capture->get(), 2);
  EXPECT_EQ(window.loaded_frames(), 0);
  for (int frame : {0, 1, 2, 0, 3, 4, 1, 2, 2, 4, 0, 3}) {
    const auto views = window.Get(frame);
    ASSERT_TRUE(views.ok()) << views.status().ToString();
    ASSERT_EQ((*views)->size(), 1u);
    EXPECT_EQ((**views)[0].vertex_count(), static_cast<size_t>((frame + 2) * (frame + 2)));
    EXPECT_LE(window.loaded_frames(), 2);
  }
  EXPECT_EQ(window.loaded_frames(), 2);
  EXPECT_FALSE(window.Get(5).ok());
  EXPECT_LE(window.loaded_frames(), 2);

  // A frame still in the window is not reloaded: the same object comes back.
  CaptureWindow large(capture->get(), 3);
  const auto first = large.Get(1);
  ASSERT_TRUE(first.ok());
  ASSERT_TRUE(large.Get(2).ok());
  const auto again = large.Get(1);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*first, *again);
  EXPECT_EQ(large.loaded_frames(), 2);

  // Least recently used goes first: after 0, 1, 0 the next load drops frame 1, not frame 0.
  CaptureWindow lru(capture->get(), 2);
  const auto zero = lru.Get(0);
  ASSERT_TRUE(zero.ok() && lru.Get(1).ok() && lru.Get(0).ok() && lru.Get(2).ok());
  const auto zero_again = lru.Get(0);
  ASSERT_TRUE(zero_again.ok());
  EXPECT_EQ(*zero, *zero_again);  // still loaded: the very same object
}

TEST(CaptureBunnyTest, StanfordBunnyScansOverlapOncePosed) {
  MESHVID_REQUIRE_SHARED_DATA();
  const auto capture = CaptureSequence::Open(shared_data + "/bunny-range/bun.conf");
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  EXPECT_EQ((*capture)->frame_count(), 1);
  ASSERT_EQ((*capture)->view_count(), 10);
  EXPECT_EQ((*capture)->info().views[1].name, "bun045");
  const auto reference = (*capture)->LoadView(0, 0);
  const auto rotated = (*capture)->LoadView(0, 1);
  ASSERT_TRUE(reference.ok() && rotated.ok());
  // Both scans see the front of the bunny: once posed their boxes nearly coincide
  // (the bunny is about 0.15 m across).
  const Eigen::AlignedBox3f box0 = BoundingBox(*reference);
  const Eigen::AlignedBox3f box1 = BoundingBox(*rotated);
  EXPECT_LT((box0.min() - box1.min()).norm(), 0.02f);
  EXPECT_LT((box0.max() - box1.max()).norm(), 0.02f);
  // And most points of bun045 lie within 1 mm of bun000 (a 2 mm hash-grid lookup).
  const float cell = 0.002f;
  std::unordered_multimap<long long, Eigen::Vector3f> grid;
  const auto key = [&](int x, int y, int z) {
    return (static_cast<long long>(x) * 73856093LL) ^ (static_cast<long long>(y) * 19349663LL) ^
           (static_cast<long long>(z) * 83492791LL);
  };
  for (const Eigen::Vector3f& p : reference->positions) {
    grid.emplace(key(std::floor(p.x() / cell), std::floor(p.y() / cell), std::floor(p.z() / cell)),
                 p);
  }
  int close = 0;
  int tested = 0;
  for (size_t i = 0; i < rotated->vertex_count(); i += 10, ++tested) {
    const Eigen::Vector3f& p = rotated->positions[i];
    const int cx = std::floor(p.x() / cell), cy = std::floor(p.y() / cell),
              cz = std::floor(p.z() / cell);
    float best = 1e9f;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto range = grid.equal_range(key(cx + dx, cy + dy, cz + dz));
          for (auto it = range.first; it != range.second; ++it)
            best = std::min(best, (it->second - p).norm());
        }
      }
    }
    if (best < 0.001f) ++close;
  }
  EXPECT_GT(close, 0.85 * tested) << close << " of " << tested << " points within 1 mm";
}

}  // namespace
}  // namespace meshvid
