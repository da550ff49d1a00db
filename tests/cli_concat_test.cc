// `meshvid concat` and `meshvid cut`, run as the built binary: pieces of a file join back into
// it byte for byte, a cut decodes as the frames it holds, pieces of an encode join in capture
// order only, and bad inputs get an error naming the file and leave no output behind.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "codec/dec/mvid_decoder.h"
#include "format/container_writer.h"
#include "format/output_file.h"
#include "tests/decoder_test_util.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

/// 12 frames in groups 0-2, 3-4 | 5-7, 8 | 9-11 (key groups at frames 0, 5 and 9, whose
/// pictures differ in size).
const std::string kThreeKeyGroups = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v2.mvid";

TEST(ConcatCliTest, PiecesCutFromAFileJoinBackIntoItByteForByte) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const char* pieces[][2] = {{"0:5", "p1.mvid"}, {"5:9", "p2.mvid"}, {"9:", "p3.mvid"}};
  std::string joined_inputs;
  for (const auto& [frames, name] : pieces) {
    const testing::CliRun cut = testing::RunMeshvid(
        "cut '" + kThreeKeyGroups + "' --frames " + frames + " -o '" + dir.File(name) + "' -q",
        dir);
    ASSERT_EQ(cut.exit_code, 0) << cut.err;
    EXPECT_EQ(cut.err, "") << "a cut on group edges rounds nothing";
    const testing::CliRun check = testing::RunMeshvid("info --check '" + dir.File(name) + "'", dir);
    EXPECT_EQ(check.exit_code, 0) << name << ": " << check.out << check.err;
    joined_inputs += " '" + dir.File(name) + "'";
  }
  // The second piece starts at key group 1: its header gives that key group's picture size.
  std::unique_ptr<MvidDecoder> second = testing::OpenDecoderOrFail(dir.File("p2.mvid"));
  ASSERT_NE(second, nullptr);
  EXPECT_EQ(second->info().frame_count, 4u);
  EXPECT_EQ(second->info().picture_height, 24);
  const testing::CliRun joined =
      testing::RunMeshvid("concat" + joined_inputs + " -o '" + dir.File("joined.mvid") + "'", dir);
  ASSERT_EQ(joined.exit_code, 0) << joined.err;
  EXPECT_NE(joined.err.find("12 frames, 3 key groups"), std::string::npos) << joined.err;
  // The golden file's header leaves its frame count unknown; a whole-file cut states it, as
  // the join does.
  const testing::CliRun whole = testing::RunMeshvid(
      "cut '" + kThreeKeyGroups + "' --frames 0: -o '" + dir.File("whole.mvid") + "' -q", dir);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(testing::ReadFile(dir.File("joined.mvid")), testing::ReadFile(dir.File("whole.mvid")));
}

// A cut that starts in a later key group states that key group's picture size in HEAD for
// every stream, the colour stream's too (spec/mvid-codec.md: both streams have the size of
// key group 0's layout), and decodes with its colours.
TEST(ConcatCliTest, ACutOfAColourFileGivesEveryStreamItsFirstKeyGroupsSize) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  testing::CliRun run = testing::RunMeshvid(
      "simulate scene:arm-block -o '" + dir.File("cap") + "' --frames 0:8 --res 160x120 -q", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = testing::RunMeshvid(
      "encode '" + dir.File("cap/manifest.json") + "' -q -o '" + dir.File("a.mvid") + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::unique_ptr<MvidDecoder> whole = testing::OpenDecoderOrFail(dir.File("a.mvid"));
  ASSERT_NE(whole, nullptr);
  ASSERT_TRUE(whole->info().colour);
  // The first key group whose pictures differ in size from key group 0's.
  const auto first_size = whole->PictureSizeOf(0);
  ASSERT_TRUE(first_size.ok());
  std::uint32_t from = 0;
  for (const MvidKeyGroupSpan& span : whole->info().key_groups) {
    const auto size = whole->PictureSizeOf(span.first_frame);
    ASSERT_TRUE(size.ok());
    if (*size != *first_size) {
      from = span.first_frame;
      break;
    }
  }
  ASSERT_GT(from, 0u) << "every key group of this capture has key group 0's picture size";
  run = testing::RunMeshvid("cut '" + dir.File("a.mvid") + "' --frames " + std::to_string(from) +
                                ": -o '" + dir.File("cut.mvid") + "' -q",
                            dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = testing::RunMeshvid("info --check '" + dir.File("cut.mvid") + "'", dir);
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  std::unique_ptr<MvidDecoder> cut = testing::OpenDecoderOrFail(dir.File("cut.mvid"));
  ASSERT_NE(cut, nullptr);
  const auto expected = whole->PictureSizeOf(from);
  ASSERT_TRUE(expected.ok());
  EXPECT_EQ(cut->info().picture_width, expected->first);
  EXPECT_EQ(cut->info().picture_height, expected->second);
  std::vector<Colour> a, b;
  ASSERT_TRUE(whole->DecodeColours(from, 1, &a).ok());
  ASSERT_TRUE(cut->DecodeColours(0, 1, &b).ok());
  EXPECT_EQ(a, b);
}

TEST(ConcatCliTest, ACutRoundsOutToItsGroupsSaysSoAndDecodesAsThoseFrames) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const testing::CliRun cut = testing::RunMeshvid(
      "cut '" + kThreeKeyGroups + "' --frames 4:10 -o '" + dir.File("cut.mvid") + "'", dir);
  ASSERT_EQ(cut.exit_code, 0) << cut.err;
  EXPECT_NE(cut.err.find("frames 4:10 rounded out to 3:12"), std::string::npos) << cut.err;
  std::unique_ptr<MvidDecoder> original = testing::OpenDecoderOrFail(kThreeKeyGroups);
  std::unique_ptr<MvidDecoder> part = testing::OpenDecoderOrFail(dir.File("cut.mvid"));
  ASSERT_NE(original, nullptr);
  ASSERT_NE(part, nullptr);
  ASSERT_EQ(part->info().frame_count, 9u);
  for (std::uint32_t f = 0; f < 9; ++f) {
    for (int level = 0; level <= part->info().levels; ++level) {
      const StatusOr<TriangleMesh> a = original->DecodeFrame(f + 3, level);
      const StatusOr<TriangleMesh> b = part->DecodeFrame(f, level);
      ASSERT_TRUE(a.ok() && b.ok()) << f;
      EXPECT_EQ(a->positions, b->positions) << "frame " << f << " level " << level;
      EXPECT_EQ(a->triangles, b->triangles) << "frame " << f << " level " << level;
    }
  }
}

TEST(ConcatCliTest, PiecesOfAnEncodeJoinInCaptureOrderOnly) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  ASSERT_EQ(testing::RunMeshvid(
                "simulate scene:arm-block -o '" + dir.File("cap") + "' --frames 0:4 -q", dir)
                .exit_code,
            0);
  for (const char* frames : {"0:2", "2:4", "3:4"}) {
    std::string name = std::string("f") + frames + ".mvid";
    name[name.find(':')] = '-';
    const testing::CliRun enc =
        testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' --frames " + frames +
                                " --levels 1 -q -o '" + dir.File(name) + "'",
                            dir);
    ASSERT_EQ(enc.exit_code, 0) << enc.err;
  }
  const testing::CliRun joined =
      testing::RunMeshvid("concat '" + dir.File("f0-2.mvid") + "' '" + dir.File("f2-4.mvid") +
                              "' -q -o '" + dir.File("joined.mvid") + "'",
                          dir);
  ASSERT_EQ(joined.exit_code, 0) << joined.err;
  EXPECT_EQ(joined.err, "");
  const testing::CliRun info =
      testing::RunMeshvid("info --check --json - '" + dir.File("joined.mvid") + "'", dir);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json described = nlohmann::json::parse(info.out);
  EXPECT_EQ(described["frames"], 4);
  EXPECT_EQ(described["metadata"]["capture_frames"], nlohmann::json({0, 4}));
  // Out of order, overlapping, or with a gap: refused, naming the file, and nothing written.
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"f2-4.mvid' '" + dir.File("f0-2.mvid"), "an overlap"},
      {"f0-2.mvid' '" + dir.File("f0-2.mvid"), "an overlap"},
      {"f0-2.mvid' '" + dir.File("f3-4.mvid"), "a gap"},
  };
  for (const auto& [files, why] : refused) {
    const testing::CliRun bad = testing::RunMeshvid(
        "concat '" + dir.File(files) + "' -o '" + dir.File("bad.mvid") + "'", dir);
    EXPECT_EQ(bad.exit_code, 1) << files;
    EXPECT_NE(bad.err.find(why), std::string::npos) << bad.err;
    EXPECT_NE(bad.err.find(".mvid: holds capture frames"), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir.File("bad.mvid"))) << files;
  }
}

/// A made-up container (opaque payloads: concat reads no codec) of `frames` frames in one
/// group, coded with `codec`.
void WriteMadeUpFile(const std::string& path, const std::string& codec, std::uint32_t frames) {
  StatusOr<std::unique_ptr<OutputFile>> file = OutputFile::Open(path);
  ASSERT_TRUE(file.ok());
  ContainerWriter writer(OstreamSink((*file)->stream(), path));
  ContainerHeader header;
  header.frame_count = frames;
  header.gof_size = 4;
  header.level_count = 1;
  header.streams = {{codec, 64, 8, 10, "displacement"}};
  ASSERT_TRUE(writer.Begin(header).ok());
  ASSERT_TRUE(writer.WriteBase(std::vector<std::uint8_t>{1, 2, 3}).ok());
  GroupOfFrames gof;
  gof.frame_count = frames;
  gof.packets.assign(1, std::vector<std::vector<std::uint8_t>>(frames, {7}));
  ASSERT_TRUE(writer.WriteGof(gof).ok());
  ASSERT_TRUE(writer.Finish().ok());
  ASSERT_TRUE((*file)->Commit().ok());
}

TEST(ConcatCliTest, RefusesFilesThatDoNotFitTogetherAndLeavesNothingBehind) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  WriteMadeUpFile(dir.File("hevc.mvid"), "hevc", 3);
  WriteMadeUpFile(dir.File("av1.mvid"), "av01", 2);
  std::string truncated = testing::ReadFile(dir.File("hevc.mvid"));
  truncated.resize(truncated.size() - 30);
  testing::WriteFile(dir.File("truncated.mvid"), truncated);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"concat '" + dir.File("hevc.mvid") + "' '" + dir.File("av1.mvid") + "'",
       "av1.mvid: stream 0 displacement av01 10-bit where the first file has displacement "
       "hevc 10-bit"},
      {"concat '" + dir.File("hevc.mvid") + "' '" + dir.File("truncated.mvid") + "'",
       "truncated.mvid: truncated or damaged"},
      {"cut '" + dir.File("truncated.mvid") + "' --frames 0:1", "truncated.mvid: truncated"},
      {"cut '" + dir.File("hevc.mvid") + "' --frames 5:9", "--frames"},
  };
  for (const auto& [command, message] : cases) {
    const testing::CliRun run =
        testing::RunMeshvid(command + " -o '" + dir.File("out.mvid") + "'", dir);
    EXPECT_EQ(run.exit_code, 1) << command;
    EXPECT_NE(run.err.find(message), std::string::npos) << command << "\n" << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir.File("out.mvid"))) << command;
  }
  // Made-up files with the same codec join (nothing is decoded).
  const testing::CliRun joined =
      testing::RunMeshvid("concat '" + dir.File("hevc.mvid") + "' '" + dir.File("hevc.mvid") +
                              "' -q -o '" + dir.File("out.mvid") + "'",
                          dir);
  EXPECT_EQ(joined.exit_code, 0) << joined.err;
}

}  // namespace
}  // namespace meshvid
