// `meshvid transcode`, run as the built binary: the displacement video is coded again and
// nothing else changes (base meshes, motion and transforms byte for byte, the same triangles,
// positions within the video's error), FFV1 to FFV1 changes nothing at all, and bad inputs get
// an error naming the file and leave no output behind.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "codec/dec/mvid_decoder.h"
#include "format/container_reader.h"
#include "tests/decoder_test_util.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

/// FFV1, 12 frames in 3 key groups whose pictures differ in size.
const std::string kThreeKeyGroups = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v2.mvid";

/// Largest distance between corresponding vertices of every frame at every level; the
/// triangles must be the same.
double LargestMove(MvidDecoder& a, MvidDecoder& b) {
  double largest = 0;
  for (std::uint32_t f = 0; f < a.info().frame_count; ++f) {
    for (int level = 0; level <= a.info().levels; ++level) {
      const StatusOr<TriangleMesh> x = a.DecodeFrame(f, level);
      const StatusOr<TriangleMesh> y = b.DecodeFrame(f, level);
      EXPECT_TRUE(x.ok() && y.ok()) << "frame " << f;
      if (!x.ok() || !y.ok()) return INFINITY;
      EXPECT_EQ(x->triangles, y->triangles) << "frame " << f << " level " << level;
      EXPECT_EQ(x->positions.size(), y->positions.size());
      for (std::size_t i = 0; i < x->positions.size() && i < y->positions.size(); ++i) {
        largest = std::max(largest, double((x->positions[i] - y->positions[i]).norm()));
      }
    }
  }
  return largest;
}

TEST(TranscodeCliTest, Av1KeepsBaseMotionAndTransformsAndMovesVerticesByTheVideosError) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string out = dir.File("sphere.av1.mvid");
  const testing::CliRun run = testing::RunMeshvid(
      "transcode '" + kThreeKeyGroups + "' --codec av1 --quality 80 -o '" + out + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("(ffv1) into"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("12 frames"), std::string::npos) << run.err;

  const testing::CliRun info = testing::RunMeshvid("info --check --json - '" + out + "'", dir);
  ASSERT_EQ(info.exit_code, 0) << info.out << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["codec"], "av1");
  EXPECT_EQ(j["frames"], 12);
  EXPECT_EQ(j["key_groups"].size(), 3u);
  EXPECT_EQ(j["metadata"]["transcoded"]["from"], "ffv1");
  EXPECT_EQ(j["metadata"]["transcoded"]["quality"], 80);

  // Every key group's BASE and MOTN byte for byte; every frame's transforms the same.
  StatusOr<ContainerReader> before = ContainerReader::OpenFile(kThreeKeyGroups);
  StatusOr<ContainerReader> after = ContainerReader::OpenFile(out);
  ASSERT_TRUE(before.ok() && after.ok());
  ASSERT_EQ(before->key_groups().size(), after->key_groups().size());
  for (std::size_t k = 0; k < before->key_groups().size(); ++k) {
    EXPECT_EQ(*before->ReadBase(k), *after->ReadBase(k)) << "key group " << k;
    EXPECT_EQ(*before->ReadMotion(k), *after->ReadMotion(k)) << "key group " << k;
  }
  std::unique_ptr<MvidDecoder> original = testing::OpenDecoderOrFail(kThreeKeyGroups);
  std::unique_ptr<MvidDecoder> transcoded = testing::OpenDecoderOrFail(out);
  ASSERT_NE(original, nullptr);
  ASSERT_NE(transcoded, nullptr);
  for (std::uint32_t f = 0; f < 12; ++f) {
    const auto a = original->DecodeTransforms(f);
    const auto b = transcoded->DecodeTransforms(f);
    ASSERT_TRUE(a.ok() && b.ok());
    for (std::size_t s = 0; s < a->size() && s < b->size(); ++s) {
      EXPECT_TRUE((*a)[s].rotation.coeffs() == (*b)[s].rotation.coeffs() &&
                  (*a)[s].translation == (*b)[s].translation)
          << "frame " << f << " segment " << s;
    }
  }
  // The vertices move only by what the lossy video changes in the displacements: well under
  // a hundredth of the sphere's unit radius at quality 80.
  const double moved = LargestMove(*original, *transcoded);
  EXPECT_LT(moved, 0.01);
}

TEST(TranscodeCliTest, Ffv1ToFfv1ChangesNoPosition) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string out = dir.File("again.mvid");
  const testing::CliRun run =
      testing::RunMeshvid("transcode '" + kThreeKeyGroups + "' --codec ffv1 -o '" + out + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("moved by 0 RMS, 0 at most"), std::string::npos) << run.err;
  std::unique_ptr<MvidDecoder> original = testing::OpenDecoderOrFail(kThreeKeyGroups);
  std::unique_ptr<MvidDecoder> transcoded = testing::OpenDecoderOrFail(out);
  ASSERT_NE(original, nullptr);
  ASSERT_NE(transcoded, nullptr);
  EXPECT_EQ(LargestMove(*original, *transcoded), 0.0);
}

/// Largest difference of a channel between the decoded colours of every frame at the finest
/// level.
int LargestColourChange(MvidDecoder& a, MvidDecoder& b) {
  int largest = 0;
  std::vector<Colour> x, y;
  for (std::uint32_t f = 0; f < a.info().frame_count; ++f) {
    const bool ok = a.DecodeColours(f, a.info().levels, &x).ok() &&
                    b.DecodeColours(f, b.info().levels, &y).ok();
    EXPECT_TRUE(ok) << "frame " << f;
    EXPECT_EQ(x.size(), y.size());
    if (!ok || x.size() != y.size()) return 256;
    for (std::size_t i = 0; i < x.size(); ++i) {
      largest = std::max(largest, (x[i].cast<int>() - y[i].cast<int>()).cwiseAbs().maxCoeff());
    }
  }
  return largest;
}

// A file with a colour stream: its colour video is coded again with the displacements'.
TEST(TranscodeCliTest, TheColourStreamIsCodedAgainToo) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string colour = std::string(MESHVID_GOLDEN_DIR) + "/sphere.colour.mvid";
  std::unique_ptr<MvidDecoder> original = testing::OpenDecoderOrFail(colour);
  ASSERT_NE(original, nullptr);
  ASSERT_TRUE(original->info().colour);
  testing::CliRun run = testing::RunMeshvid(
      "transcode '" + colour + "' --codec ffv1 -o '" + dir.File("ffv1.mvid") + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::unique_ptr<MvidDecoder> again = testing::OpenDecoderOrFail(dir.File("ffv1.mvid"));
  ASSERT_NE(again, nullptr);
  EXPECT_TRUE(again->info().colour);
  EXPECT_EQ(LargestColourChange(*original, *again), 0);
  run = testing::RunMeshvid(
      "transcode '" + colour + "' --codec av1 --quality 90 -o '" + dir.File("av1.mvid") + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::unique_ptr<MvidDecoder> av1 = testing::OpenDecoderOrFail(dir.File("av1.mvid"));
  ASSERT_NE(av1, nullptr);
  EXPECT_EQ(av1->info().codec, VideoCodec::kAv1);
  EXPECT_TRUE(av1->info().colour);
  const int change = LargestColourChange(*original, *av1);
  EXPECT_GT(change, 0);  // coded again, lossily
  EXPECT_LE(change, 24);
  run = testing::RunMeshvid("info --check '" + dir.File("av1.mvid") + "'", dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
}

TEST(TranscodeCliTest, AVersionOneFileTranscodesAndPicturesACodecRefusesAreAClearError) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string v1 = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v1.mvid";
  const testing::CliRun av1 =
      testing::RunMeshvid("transcode '" + v1 + "' -q -o '" + dir.File("v1.av1.mvid") + "'", dir);
  ASSERT_EQ(av1.exit_code, 0) << av1.err;
  EXPECT_EQ(testing::RunMeshvid("info --check '" + dir.File("v1.av1.mvid") + "'", dir).exit_code,
            0);
  // x265 refuses the file's 64x8 pictures: an error naming the group, the size and the way
  // out (exit 1, not an internal error), and no output.
  const testing::CliRun hevc = testing::RunMeshvid(
      "transcode '" + v1 + "' --codec hevc -o '" + dir.File("v1.hevc.mvid") + "'", dir);
  EXPECT_EQ(hevc.exit_code, 1);
  EXPECT_NE(hevc.err.find("group 0: hevc cannot code this key group's 64x8 pictures"),
            std::string::npos)
      << hevc.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("v1.hevc.mvid")));
}

TEST(TranscodeCliTest, BadInputsGetAnErrorAndLeaveNothingBehind) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string out = dir.File("out.mvid");
  // A truncated file: refused, naming it.
  const std::string bytes = testing::ReadFile(kThreeKeyGroups);
  testing::WriteFile(dir.File("short.mvid"), bytes.substr(0, bytes.size() * 2 / 3));
  const testing::CliRun truncated =
      testing::RunMeshvid("transcode '" + dir.File("short.mvid") + "' -o '" + out + "'", dir);
  EXPECT_EQ(truncated.exit_code, 1);
  EXPECT_NE(truncated.err.find("short.mvid"), std::string::npos) << truncated.err;
  // Not a .mvid at all.
  testing::WriteFile(dir.File("text.mvid"), "hello");
  const testing::CliRun text =
      testing::RunMeshvid("transcode '" + dir.File("text.mvid") + "' -o '" + out + "'", dir);
  EXPECT_EQ(text.exit_code, 1);
  EXPECT_NE(text.err.find("text.mvid"), std::string::npos) << text.err;
  // The output may not be the input.
  testing::WriteFile(dir.File("copy.mvid"), bytes);
  const testing::CliRun same = testing::RunMeshvid(
      "transcode '" + dir.File("copy.mvid") + "' -o '" + dir.File("copy.mvid") + "'", dir);
  EXPECT_EQ(same.exit_code, 1);
  EXPECT_NE(same.err.find("is the input"), std::string::npos) << same.err;
  EXPECT_EQ(testing::ReadFile(dir.File("copy.mvid")), bytes);
  // A wrong command line: the usage code.
  EXPECT_EQ(testing::RunMeshvid("transcode '" + kThreeKeyGroups + "' --codec vp9 -o x.mvid", dir)
                .exit_code,
            2);
  EXPECT_EQ(testing::RunMeshvid("transcode '" + kThreeKeyGroups + "' --quality 101 -o x.mvid", dir)
                .exit_code,
            2);
  // Nothing written, not even a temporary file.
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name != "out.mvid" && name.find("partial") == std::string::npos) << name;
  }
}

}  // namespace
}  // namespace meshvid
