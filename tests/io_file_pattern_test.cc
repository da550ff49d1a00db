// Tests of FilePattern (parse, expand, scan) and ParseFrameRange.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <utility>

#include "tests/test_util.h"
#include "tools/io/file_pattern.h"

namespace meshvid {
namespace {

using testing::TempDir;
using testing::WriteFile;

TEST(FilePatternTest, ParsesPlaceholdersAndExpandsWithWidths) {
  const StatusOr<FilePattern> pattern = FilePattern::Parse("cap/f{frame:04}_v{view}.ply");
  ASSERT_TRUE(pattern.ok()) << pattern.status().ToString();
  EXPECT_TRUE(pattern->has_frame());
  EXPECT_TRUE(pattern->has_view());
  EXPECT_EQ(pattern->pattern(), "cap/f{frame:04}_v{view}.ply");
  EXPECT_EQ(pattern->Expand(7, 2), "cap/f0007_v2.ply");
  EXPECT_EQ(pattern->Expand(0, 0), "cap/f0000_v0.ply");
  EXPECT_EQ(pattern->Expand(12345, 10), "cap/f12345_v10.ply");  // wider than the width

  const StatusOr<FilePattern> frame_only = FilePattern::Parse("m{frame}.obj");
  ASSERT_TRUE(frame_only.ok());
  EXPECT_TRUE(frame_only->has_frame());
  EXPECT_FALSE(frame_only->has_view());
  EXPECT_EQ(frame_only->Expand(42, 9), "m42.obj");

  const StatusOr<FilePattern> view_first = FilePattern::Parse("/abs/{view:02}-{frame:03}.png");
  ASSERT_TRUE(view_first.ok());
  EXPECT_EQ(view_first->Expand(5, 3), "/abs/03-005.png");
}

TEST(FilePatternTest, RejectsMalformedPatterns) {
  for (const char* bad :
       {"f{frame:4}.ply", "f{frame:0}.ply", "f{frame:0x}.ply", "f{foo}.ply", "f{frame}{frame}.ply",
        "d{frame}/x{view}.ply", "f{frame.ply", "f}{frame}.ply", "dir/"}) {
    const StatusOr<FilePattern> pattern = FilePattern::Parse(bad);
    ASSERT_FALSE(pattern.ok()) << bad;
    EXPECT_EQ(pattern.status().code(), StatusCode::kInvalidArgument) << bad;
    EXPECT_NE(pattern.status().message().find(bad), std::string::npos)
        << pattern.status().message();
  }
  EXPECT_EQ(FilePattern::Parse("f{frame:4}.ply").status().message(),
            "pattern 'f{frame:4}.ply': bad width in '{frame:4}' (write a zero-padded width "
            "like {frame:04})");
  EXPECT_EQ(FilePattern::Parse("f{frame}_{frame}.ply").status().message(),
            "pattern 'f{frame}_{frame}.ply': {frame} appears more than once");
}

TEST(FilePatternTest, LooksLikePattern) {
  EXPECT_TRUE(FilePattern::LooksLikePattern("a/f{frame}.ply"));
  EXPECT_TRUE(FilePattern::LooksLikePattern("a/f{frame:04}.ply"));
  EXPECT_TRUE(FilePattern::LooksLikePattern("v{view}.ply"));
  EXPECT_FALSE(FilePattern::LooksLikePattern("a/f0001.ply"));
  EXPECT_FALSE(FilePattern::LooksLikePattern("a/{x}.ply"));
}

TEST(FilePatternTest, ScanHonoursWidths) {
  TempDir dir;
  for (const char* name :
       {"f0000_v0.ply", "f0000_v1.ply", "f0001_v0.ply", "f12345_v0.ply", "f001_v0.ply",
        "f00002_v0.ply", "g0000_v0.ply", "f0000_v0.ply.bak", "f0003_vx.ply"}) {
    WriteFile(dir.File(name), "x");
  }
  const StatusOr<FilePattern> pattern = FilePattern::Parse(dir.File("f{frame:04}_v{view}.ply"));
  ASSERT_TRUE(pattern.ok());
  const auto files = pattern->Scan();
  ASSERT_TRUE(files.ok()) << files.status().ToString();
  const std::map<std::pair<int, int>, std::string> expected = {
      {{0, 0}, dir.File("f0000_v0.ply")},
      {{0, 1}, dir.File("f0000_v1.ply")},
      {{1, 0}, dir.File("f0001_v0.ply")},
      {{12345, 0}, dir.File("f12345_v0.ply")}};
  EXPECT_EQ(*files, expected);
}

TEST(FilePatternTest, ScanWithoutWidthAcceptsAnyDigitsButNotDuplicates) {
  TempDir dir;
  for (const char* name : {"a1.obj", "a10.obj", "a007.obj", "a.obj", "ab2.obj"}) {
    WriteFile(dir.File(name), "x");
  }
  const StatusOr<FilePattern> pattern = FilePattern::Parse(dir.File("a{frame}.obj"));
  ASSERT_TRUE(pattern.ok());
  const auto files = pattern->Scan();
  ASSERT_TRUE(files.ok());
  const std::map<std::pair<int, int>, std::string> expected = {
      {{1, 0}, dir.File("a1.obj")}, {{7, 0}, dir.File("a007.obj")}, {{10, 0}, dir.File("a10.obj")}};
  EXPECT_EQ(*files, expected);

  WriteFile(dir.File("a7.obj"), "x");
  const auto duplicate = pattern->Scan();
  ASSERT_FALSE(duplicate.ok());
  EXPECT_NE(duplicate.status().message().find("both match frame 7"), std::string::npos)
      << duplicate.status().message();
}

TEST(FilePatternTest, ScanOfMissingFolderFails) {
  TempDir dir;
  const StatusOr<FilePattern> pattern = FilePattern::Parse(dir.File("nope/f{frame}.ply"));
  ASSERT_TRUE(pattern.ok());
  const auto files = pattern->Scan();
  ASSERT_FALSE(files.ok());
  EXPECT_EQ(files.status().code(), StatusCode::kNotFound);
  EXPECT_NE(files.status().message().find(dir.File("nope")), std::string::npos);
}

TEST(FrameRangeTest, ParsesEveryForm) {
  using Range = std::pair<int, int>;
  EXPECT_EQ(*ParseFrameRange("2:5", 10), Range(2, 5));
  EXPECT_EQ(*ParseFrameRange("3:", 10), Range(3, 10));
  EXPECT_EQ(*ParseFrameRange(":4", 10), Range(0, 4));
  EXPECT_EQ(*ParseFrameRange(":", 10), Range(0, 10));
  EXPECT_EQ(*ParseFrameRange("7", 10), Range(7, 8));
  EXPECT_EQ(*ParseFrameRange("0:100", 10), Range(0, 10));  // clamped
}

TEST(FrameRangeTest, SaysWhenAnExplicitEndIsClipped) {
  std::string clipped = "stale";
  EXPECT_EQ(*ParseFrameRange("8:20", 10, &clipped), std::make_pair(8, 10));
  EXPECT_EQ(clipped, "frame range '8:20' runs past the last of the 10 frames: using 8:10");
  for (const char* within : {"8:10", "8:", ":", "9"}) {
    ASSERT_TRUE(ParseFrameRange(within, 10, &clipped).ok()) << within;
    EXPECT_EQ(clipped, "") << within;
  }
}

TEST(FrameRangeTest, RejectsEmptyAndMalformedRanges) {
  for (const char* bad : {"5:5", "9:3", "12", "10:", "a:b", "-1:3", "", "1:2:3", "3 ", "x"}) {
    const auto range = ParseFrameRange(bad, 10);
    ASSERT_FALSE(range.ok()) << bad;
    EXPECT_EQ(range.status().code(), StatusCode::kInvalidArgument) << bad;
  }
  EXPECT_EQ(ParseFrameRange("12", 10).status().message(),
            "frame range '12' selects no frame of the 10 frames (0..9)");
  EXPECT_EQ(ParseFrameRange("a:b", 10).status().message(),
            "frame range 'a:b' is malformed: expected A:B (frames A..B-1), A:, :B or N, with "
            "non-negative integers");
}

}  // namespace
}  // namespace meshvid
