// `meshvid encode` end to end on simulated captures, run as the built binary: errors, the
// summary, rate, accuracy and coverage against the ground truth, and the segmentation of the
// arm-block scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "codec/dec/mvid_decoder.h"
#include "tests/test_util.h"
#include "tools/sim/ground_truth.h"
#include "tools/sim/scenes.h"

namespace meshvid {
namespace {

TEST(EncodeCliTest, ExplainsBadInputAndLeavesNoFileBehind) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string out = dir.File("out.mvid");
  testing::CliRun run = testing::RunMeshvid("encode '" + dir.File("nope.json") + "' -o '" + out + "'", dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("nope.json"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(out + ".partial"));

  run = testing::RunMeshvid("simulate scene:arm-block -o '" + dir.File("cap") + "' --frames 0:2 -q", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                "' --quality 120 -q",
                            dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--quality"), std::string::npos) << run.err;
  // The library names EncoderOptions' fields (tolerance_shrink); the command, its flags.
  run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                "' --tol-shrink 2 -q",
                            dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--tol-shrink must be in (0, 1)"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("tolerance_shrink"), std::string::npos) << run.err;
  run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                "' --base-voxel-scale 0 -q",
                            dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--base-voxel-scale must be in [0.25, 8]"), std::string::npos)
      << run.err;
  run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                "' --codec mpeg2 -q",
                            dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("mpeg2"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // By default the whole base surface is decoded; --hide-unseen writes the mask of base
  // triangles no view saw.
  for (const char* flag : {"", " --hide-unseen"}) {
    run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                  "' -q" + flag,
                              dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    auto decoder = MvidDecoder::OpenFile(out);
    ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
    const auto& mask = (*decoder)->motion().surface_triangles;
    if (*flag == '\0') {
      EXPECT_TRUE(mask.empty());
    } else {
      ASSERT_EQ(mask.size(), (*decoder)->base_mesh().triangle_count());
      EXPECT_GT(std::count(mask.begin(), mask.end(), 0), 0) << "the back was never seen";
      EXPECT_GT(std::count(mask.begin(), mask.end(), 1), 0);
    }
  }
  std::filesystem::remove(out);
  run = testing::RunMeshvid("encode --help", dir);
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("--occlusion-frames"), std::string::npos);
}

/// Simulates `frames` frames of the arm-block scene and encodes them.
class ArmBlockEncode : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!testing::HaveMeshvidCli()) return;
    dir_ = new testing::TempDir;
    const testing::CliRun sim = testing::RunMeshvid(
        "simulate scene:arm-block -o '" + dir_->File("cap") + "' --frames 0:" +
            std::to_string(kFrames) + " -q",
        *dir_);
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    const testing::CliRun enc = testing::RunMeshvid(
        "encode '" + dir_->File("cap/manifest.json") + "' -o '" + dir_->File("arm.mvid") +
            "' --levels 2 --summary-json '" + dir_->File("summary.json") + "'",
        *dir_);
    encode_exit_ = enc.exit_code;
    encode_err_ = enc.err;
  }
  static void TearDownTestSuite() { delete dir_; }
  void SetUp() override {
    MESHVID_REQUIRE_CLI();
    ASSERT_EQ(encode_exit_, 0) << encode_err_;
  }
  static constexpr int kFrames = 16;
  static testing::TempDir* dir_;
  static int encode_exit_;
  static std::string encode_err_;
};
testing::TempDir* ArmBlockEncode::dir_ = nullptr;
int ArmBlockEncode::encode_exit_ = -1;
std::string ArmBlockEncode::encode_err_;

TEST_F(ArmBlockEncode, SummaryStatesTheStreamsAndRate) {
  EXPECT_NE(encode_err_.find("segments"), std::string::npos) << encode_err_;
  EXPECT_NE(encode_err_.find("Mbit/s"), std::string::npos) << encode_err_;
  const nlohmann::json s = nlohmann::json::parse(testing::ReadFile(dir_->File("summary.json")));
  EXPECT_EQ(s["frames"], kFrames);
  EXPECT_EQ(s["views"], 3);
  EXPECT_GE(s["segments"].get<int>(), 2);
  const auto total = s["bytes_total"].get<std::uint64_t>();
  EXPECT_EQ(total, std::filesystem::file_size(dir_->File("arm.mvid")));
  EXPECT_GE(total, s["bytes_base"].get<std::uint64_t>() + s["bytes_motion"].get<std::uint64_t>() +
                       s["bytes_transforms"].get<std::uint64_t>() +
                       s["bytes_video"].get<std::uint64_t>());
  EXPECT_LT(s["bytes_video"].get<std::uint64_t>(), total);
  EXPECT_GT(s["filled_share"].get<double>(), 0.0);
  EXPECT_LT(s["filled_share"].get<double>(), 1.0);
}

TEST_F(ArmBlockEncode, DecodedSequenceCoversAtLeastTheInputAndStaysNearTheTruth) {
  const std::string gt = dir_->File("cap/ground_truth.obj");
  testing::CliRun run = testing::RunMeshvid(
      "eval --ref '" + gt + "' --test '" + dir_->File("arm.mvid") + "' --samples 40000 -q --json '" +
          dir_->File("mvid.json") + "'",
      *dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = testing::RunMeshvid("eval --ref '" + gt + "' --test '" + dir_->File("cap/manifest.json") +
                                "' --samples 40000 -q --json '" + dir_->File("raw.json") + "'",
                            *dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto mvid = nlohmann::json::parse(testing::ReadFile(dir_->File("mvid.json")))["mean"];
  const auto raw = nlohmann::json::parse(testing::ReadFile(dir_->File("raw.json")))["mean"];
  EXPECT_GE(mvid["coverage"].get<double>(), raw["coverage"].get<double>()) << mvid << raw;
  // A regression guard at the measured level (about 30 mm RMS on these 16 frames: the
  // tracking of the fast arm lags; issue 4's goal, under the 1 mm sensor noise, is not met).
  EXPECT_LT(mvid["accuracy_rms"].get<double>(), 0.05) << mvid;
}

TEST_F(ArmBlockEncode, TheBlockLandsInOneSegment) {
  auto decoder = MvidDecoder::OpenFile(dir_->File("arm.mvid"));
  ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
  auto truth = OpenGroundTruth("scene:arm-block");
  ASSERT_TRUE(truth.ok());
  auto frame0 = (*truth)->Frame(0);
  ASSERT_TRUE(frame0.ok());
  const std::vector<std::string> parts = ArmBlockVertexParts();
  const TriangleMesh& base = (*decoder)->base_mesh();
  const MotionModel& motion = (*decoder)->motion();
  // Each base vertex takes the part of the nearest ground-truth vertex and votes for its
  // strongest segment.
  std::map<std::string, std::map<std::uint32_t, int>> votes;
  std::map<std::string, int> totals;
  for (std::size_t v = 0; v < base.vertex_count(); ++v) {
    std::size_t nearest = 0;
    float best = 1e30f;
    for (std::size_t g = 0; g < frame0->vertex_count(); ++g) {
      const float d = (frame0->positions[g] - base.positions[v]).squaredNorm();
      if (d < best) best = d, nearest = g;
    }
    if (best > 0.01f * 0.01f) continue;  // base vertices away from the object (fused hull)
    const VertexBlend& blend = motion.blends[v];
    const auto strongest = std::max_element(
        blend.influences.begin(), blend.influences.begin() + blend.count,
        [](const BlendInfluence& a, const BlendInfluence& b) { return a.weight < b.weight; });
    ++votes[parts[nearest]][strongest->segment];
    ++totals[parts[nearest]];
  }
  ASSERT_GT(totals["block"], 50);
  std::map<std::string, double> shares;
  for (const auto& [part, part_votes] : votes) {
    int top = 0;
    for (const auto& [segment, count] : part_votes) top = std::max(top, count);
    shares[part] = double(top) / totals[part];
    std::printf("%s: %.1f%% of %d base vertices in one segment\n", part.c_str(),
                100 * shares[part], totals[part]);
  }
  // Regression guards at the measured levels. With the distance-volume fusion's base (open
  // where no view looks) the arm holds together far better (80.7%, was 45.2% on the closed
  // Poisson base) and the block a little worse (88.6%, was 95.9%). The base ended where the
  // cameras saw through it (0.8% of frame 0's fused triangles removed, --free-space) gives
  // block 99.3%, arm 63.9% (80.1% and 100% with --free-space false): the segmentation of the
  // fast arm moves with small changes of the base. Issue 4's goal of 95% for both is not met.
  EXPECT_GE(shares["block"], 0.85);
  EXPECT_GE(shares["arm"], 0.6);
}

}  // namespace
}  // namespace meshvid
