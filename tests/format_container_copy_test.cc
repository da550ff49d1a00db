// Copying groups of frames between containers (format/container_copy.h): chunks byte for byte,
// GOFs renumbered, each key group's BASE and MOTN before its first copied GOF; and the checks
// that decide whether files can be joined.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "format/container_copy.h"
#include "format/container_reader.h"
#include "format/container_writer.h"

namespace meshvid {
namespace {

std::vector<std::uint8_t> Bytes(const std::string& text) { return {text.begin(), text.end()}; }

ContainerHeader Header(std::uint32_t frame_count) {
  ContainerHeader header;
  header.frame_rate_numerator = 25025;
  header.frame_rate_denominator = 1001;
  header.frame_count = frame_count;
  header.gof_size = 3;
  header.level_count = 2;
  header.streams = {{"hevc", 64, 32, 10, "displacement"}};
  header.metadata_json = R"({"capture":"c"})";
  return header;
}

/// A writer appending to `file`.
ContainerWriter WriterInto(std::vector<std::uint8_t>* file) {
  return ContainerWriter([file](std::span<const std::uint8_t> bytes) {
    file->insert(file->end(), bytes.begin(), bytes.end());
    return Status::Ok();
  });
}

GroupOfFrames Gof(std::uint32_t index, std::uint32_t first, std::uint32_t count,
                  const std::string& tag) {
  GroupOfFrames gof;
  gof.gof_index = index;
  gof.first_frame = first;
  gof.frame_count = count;
  gof.transforms = Bytes("transforms " + tag);
  gof.packets.resize(1);
  for (std::uint32_t p = 0; p < count; ++p)
    gof.packets[0].push_back(Bytes(tag + std::to_string(p)));
  return gof;
}

/// Two key groups named by `tag`: frames 0-4 in GOFs of 3 and 2, then frames 5-7 in one.
std::vector<std::uint8_t> TwoKeyGroups(const std::string& tag) {
  std::vector<std::uint8_t> file;
  ContainerWriter writer = WriterInto(&file);
  EXPECT_TRUE(writer.Begin(Header(8)).ok());
  EXPECT_TRUE(writer.WriteBase(Bytes("base 0 " + tag)).ok());
  EXPECT_TRUE(writer.WriteMotion(Bytes("motion 0 " + tag)).ok());
  EXPECT_TRUE(writer.WriteGof(Gof(0, 0, 3, tag + "a")).ok());
  EXPECT_TRUE(writer.WriteGof(Gof(1, 3, 2, tag + "b")).ok());
  EXPECT_TRUE(writer.WriteBase(Bytes("base 1 " + tag)).ok());
  EXPECT_TRUE(writer.WriteMotion(Bytes("motion 1 " + tag)).ok());
  EXPECT_TRUE(writer.WriteGof(Gof(2, 5, 3, tag + "c")).ok());
  EXPECT_TRUE(writer.Finish().ok());
  return file;
}

ContainerReader Open(std::vector<std::uint8_t> file) {
  StatusOr<ContainerReader> reader = ContainerReader::OpenMemory(std::move(file));
  EXPECT_TRUE(reader.ok()) << reader.status().message();
  return *std::move(reader);
}

TEST(CopyGofs, AWholeFileCopiedIsTheSameBytes) {
  const std::vector<std::uint8_t> original = TwoKeyGroups("x");
  ContainerReader in = Open(original);
  std::vector<std::uint8_t> copy;
  ContainerWriter out = WriterInto(&copy);
  ASSERT_TRUE(out.Begin(in.header()).ok());
  ASSERT_TRUE(CopyGofs(in, 0, in.gof_count(), out).ok());
  ASSERT_TRUE(out.Finish().ok());
  EXPECT_EQ(copy, original);
}

TEST(CopyGofs, JoinedFilesFollowEachOtherWithTheirKeyGroupsWhole) {
  ContainerReader first = Open(TwoKeyGroups("x"));
  ContainerReader second = Open(TwoKeyGroups("y"));
  std::vector<std::uint8_t> joined;
  ContainerWriter out = WriterInto(&joined);
  ASSERT_TRUE(out.Begin(Header(16)).ok());
  ASSERT_TRUE(CopyGofs(first, 0, 3, out).ok());
  ASSERT_TRUE(CopyGofs(second, 0, 3, out).ok());
  ASSERT_TRUE(out.Finish().ok());
  ContainerReader result = Open(joined);
  ASSERT_TRUE(CheckWholeContainer(result, "joined").ok());
  EXPECT_EQ(result.frame_count(), 16u);
  ASSERT_EQ(result.key_groups().size(), 4u);
  EXPECT_EQ(*result.ReadBase(2), Bytes("base 0 y"));
  EXPECT_EQ(*result.ReadMotion(3), Bytes("motion 1 y"));
  const StatusOr<GroupOfFrames> moved = result.ReadGof(4);
  ASSERT_TRUE(moved.ok());
  EXPECT_EQ(moved->gof_index, 4u);
  EXPECT_EQ(moved->first_frame, 11u);  // 8 frames of the first file, then 3 of the second
  EXPECT_EQ(moved->transforms, Bytes("transforms yb"));
  EXPECT_EQ(moved->packets[0][1], Bytes("yb1"));
}

TEST(CopyGofs, ACutStartingInsideAKeyGroupGetsItsBaseAndMotion) {
  ContainerReader in = Open(TwoKeyGroups("x"));
  std::vector<std::uint8_t> cut;
  ContainerWriter out = WriterInto(&cut);
  ASSERT_TRUE(out.Begin(Header(5)).ok());
  ASSERT_TRUE(CopyGofs(in, 1, 3, out).ok());
  ASSERT_TRUE(out.Finish().ok());
  ContainerReader result = Open(cut);
  ASSERT_EQ(result.key_groups().size(), 2u);
  EXPECT_EQ(*result.ReadBase(0), Bytes("base 0 x"));
  EXPECT_EQ(result.ReadGof(0)->first_frame, 0u);
  EXPECT_EQ(result.ReadGof(0)->transforms, Bytes("transforms xb"));
  EXPECT_EQ(*result.ReadBase(1), Bytes("base 1 x"));
  EXPECT_EQ(result.ReadGof(1)->first_frame, 2u);
}

TEST(CopyGofs, RefusesARangeThatIsNotOne) {
  ContainerReader in = Open(TwoKeyGroups("x"));
  std::vector<std::uint8_t> file;
  ContainerWriter out = WriterInto(&file);
  ASSERT_TRUE(out.Begin(Header(0)).ok());
  EXPECT_EQ(CopyGofs(in, 2, 2, out).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(CopyGofs(in, 0, 4, out).code(), StatusCode::kInvalidArgument);
}

TEST(CheckJoinable, NamesWhatDiffers) {
  const ContainerHeader first = Header(8);
  ContainerHeader next = first;
  next.streams[0].width = 128;  // key groups' pictures differ in size anyway
  next.frame_count = 3;
  next.metadata_json = "{}";
  EXPECT_TRUE(CheckJoinable(first, next, "b.mvid").ok());
  next.frame_rate_numerator = 25;  // 25/1 is 25025/1001
  next.frame_rate_denominator = 1;
  EXPECT_TRUE(CheckJoinable(first, next, "b.mvid").ok());
  struct Case {
    void (*change)(ContainerHeader*);
    std::string what;
  };
  const Case cases[] = {
      {[](ContainerHeader* h) { h->frame_rate_numerator = 30; }, "frame rate"},
      {[](ContainerHeader* h) { h->level_count = 3; }, "level count"},
      {[](ContainerHeader* h) { h->gof_size = 32; }, "group size"},
      {[](ContainerHeader* h) { h->streams[0].codec = "av01"; }, "av01"},
      {[](ContainerHeader* h) { h->streams.push_back(h->streams[0]); }, "stream count"},
  };
  for (const Case& c : cases) {
    ContainerHeader changed = first;
    c.change(&changed);
    const Status status = CheckJoinable(first, changed, "b.mvid");
    EXPECT_EQ(status.code(), StatusCode::kInvalidArgument) << c.what;
    EXPECT_NE(status.message().find("b.mvid"), std::string::npos) << status.message();
    EXPECT_NE(status.message().find(c.what), std::string::npos) << status.message();
  }
}

TEST(CheckWholeContainer, RefusesATruncatedFile) {
  std::vector<std::uint8_t> file = TwoKeyGroups("x");
  file.resize(file.size() - 40);
  StatusOr<ContainerReader> reader = ContainerReader::OpenMemory(file);
  ASSERT_TRUE(reader.ok());
  const Status whole = CheckWholeContainer(*reader, "t.mvid");
  EXPECT_EQ(whole.code(), StatusCode::kCorrupt);
  EXPECT_NE(whole.message().find("t.mvid"), std::string::npos) << whole.message();
  EXPECT_TRUE(CheckWholeContainer(Open(TwoKeyGroups("x")), "x.mvid").ok());
}

}  // namespace
}  // namespace meshvid
