// `meshvid encode` of an open, thin surface: the cloth scene (a hanging sheet) seen by the
// default 3-view arc encodes, and decodes as a sheet, with a boundary, whose area is about
// the area of the cloth the views saw (no invented closing sheet behind it).
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "codec/dec/mvid_decoder.h"
#include "tests/test_util.h"
#include "tools/sim/ground_truth.h"

namespace meshvid {
namespace {

TEST(ClothEncodeTest, DecodesAsASheetOfTheSeenArea) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  testing::CliRun run =
      testing::RunMeshvid("simulate scene:cloth -o '" + dir.File("cap") + "' --frames 0:4 -q", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = testing::RunMeshvid(
      "encode '" + dir.File("cap/manifest.json") + "' -o '" + dir.File("cloth.mvid") + "' -q", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = testing::RunMeshvid("eval --ref '" + dir.File("cap/ground_truth.obj") + "' --test '" +
                                dir.File("cap/manifest.json") + "' --samples 40000 -q --json '" +
                                dir.File("views.json") + "'",
                            dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json views = nlohmann::json::parse(testing::ReadFile(dir.File("views.json")));

  auto truth = OpenGroundTruth(dir.File("cap/ground_truth.obj"));
  ASSERT_TRUE(truth.ok()) << truth.status().ToString();
  auto decoder = MvidDecoder::OpenFile(dir.File("cloth.mvid"));
  ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
  ASSERT_EQ((*decoder)->info().frame_count, 4u);
  for (int frame = 0; frame < 4; ++frame) {
    auto decoded = (*decoder)->DecodeFrame(frame, (*decoder)->info().levels);
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    EXPECT_GT(testing::BoundaryEdgeCount(*decoded), 50u)
        << "frame " << frame << " is not a sheet";
    auto truth_frame = (*truth)->Frame(frame);
    ASSERT_TRUE(truth_frame.ok()) << truth_frame.status().ToString();
    // The seen area: the share of the truth's samples near some view, times its area.
    const double seen =
        SurfaceArea(*truth_frame) * views["frames"][frame]["coverage"].get<double>();
    EXPECT_NEAR(SurfaceArea(*decoded), seen, 0.1 * seen) << "frame " << frame;
  }
}

}  // namespace
}  // namespace meshvid
