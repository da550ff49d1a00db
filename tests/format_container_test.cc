// Round trips of the .mvid container: writer -> seekable reader (by index and by scan),
// writer -> progressive stream reader, Validate's report, and the spec's hex dump.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "format/byte_io.h"
#include "format/chunk.h"
#include "format/container_reader.h"
#include "format/container_writer.h"
#include "format/crc32c.h"
#include "format/stream_reader.h"
#include "format/validate.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

std::vector<uint8_t> Bytes(const std::string& text) { return {text.begin(), text.end()}; }

ContainerHeader SampleHeader(uint32_t frame_count) {
  ContainerHeader header;
  header.frame_rate_numerator = 30000;
  header.frame_rate_denominator = 1001;
  header.frame_count = frame_count;
  header.gof_size = 4;
  header.level_count = 3;
  header.streams = {{"hevc", 256, 128, 10, "displacement"}, {"ffv1", 64, 32, 8, "mask"}};
  header.metadata_json = R"({"source":"samba","quantisation_bits":10})";
  return header;
}

// GOF k: frames [4k, 4k + count), distinct payloads per GOF, stream and packet.
GroupOfFrames SampleGof(uint32_t k, uint32_t count) {
  GroupOfFrames gof;
  gof.gof_index = k;
  gof.first_frame = 4 * k;
  gof.frame_count = count;
  gof.transforms = Bytes("transforms of gof " + std::to_string(k));
  gof.packets.resize(2);
  for (uint32_t p = 0; p < count; ++p) {
    gof.packets[0].push_back(Bytes("hevc " + std::to_string(k) + "/" + std::to_string(p)));
  }
  gof.packets[1].push_back({});  // an empty packet survives too
  gof.packets[1].push_back(Bytes(std::string(100 + k, static_cast<char>('a' + k))));
  return gof;
}

// A file with header, base, motion and 5 GOFs (18 frames, the last group shorter).
std::vector<GroupOfFrames> SampleGofs() {
  return {SampleGof(0, 4), SampleGof(1, 4), SampleGof(2, 4), SampleGof(3, 4), SampleGof(4, 2)};
}

std::vector<uint8_t> WriteSample() {
  std::vector<uint8_t> file;
  ContainerWriter writer([&](std::span<const uint8_t> bytes) {
    file.insert(file.end(), bytes.begin(), bytes.end());
    return Status::Ok();
  });
  EXPECT_TRUE(writer.Begin(SampleHeader(18)).ok());
  EXPECT_TRUE(writer.WriteBase(Bytes("draco base mesh")).ok());
  EXPECT_TRUE(writer.WriteMotion(Bytes("segments and weights")).ok());
  for (const GroupOfFrames& gof : SampleGofs()) EXPECT_TRUE(writer.WriteGof(gof).ok());
  EXPECT_TRUE(writer.Finish().ok());
  EXPECT_EQ(writer.bytes_written(), file.size());
  return file;
}

// Counts the bytes a reader pulls from its source.
class CountingSource : public MemorySource {
 public:
  using MemorySource::MemorySource;
  Status ReadAt(uint64_t offset, std::span<uint8_t> out) override {
    bytes_read += out.size();
    return MemorySource::ReadAt(offset, out);
  }
  uint64_t bytes_read = 0;
};

TEST(FormatContainerTest, RoundTripThroughIndexIsByteExact) {
  const std::vector<uint8_t> file = WriteSample();
  auto reader = ContainerReader::OpenMemory(file, "sample.mvid");
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_TRUE(reader->used_index()) << reader->index_status().ToString();
  EXPECT_EQ(reader->header(), SampleHeader(18));
  EXPECT_EQ(*reader->ReadBase(), Bytes("draco base mesh"));
  EXPECT_EQ(*reader->ReadMotion(), Bytes("segments and weights"));
  ASSERT_EQ(reader->gof_count(), 5u);
  EXPECT_EQ(reader->frame_count(), 18u);
  const auto gofs = SampleGofs();
  for (size_t k = 0; k < gofs.size(); ++k) EXPECT_EQ(*reader->ReadGof(k), gofs[k]) << k;
  EXPECT_EQ(*reader->FindGof(0), 0u);
  EXPECT_EQ(*reader->FindGof(7), 1u);
  EXPECT_EQ(*reader->FindGof(17), 4u);
  EXPECT_EQ(reader->FindGof(18).status().code(), StatusCode::kNotFound);
  EXPECT_EQ(reader->ReadGof(5).status().code(), StatusCode::kNotFound);
}

TEST(FormatContainerTest, IndexSeekReadsOnlyWhatItNeeds) {
  const std::vector<uint8_t> file = WriteSample();
  auto owned = std::make_unique<CountingSource>(file);
  CountingSource* source = owned.get();
  auto reader = ContainerReader::Open(std::move(owned));
  ASSERT_TRUE(reader.ok());
  // Open reads: preamble, HEAD chunk, TRLR, INDX chunk. Nothing else.
  const uint64_t head_chunk = kChunkHeaderSize + EncodeHeaderPayload(SampleHeader(18)).size() +
                              kChunkCrcSize;
  // key_group_count, one key group (base_offset, motion_offset, first_gof), gof_count, 5 GOFs.
  const uint64_t index_chunk = kChunkHeaderSize + 4 + 20 + 4 + 5 * 16 + kChunkCrcSize;
  EXPECT_EQ(source->bytes_read, kPreambleSize + head_chunk + kTrailerChunkSize + index_chunk);
  // Seeking to GOF 3 reads exactly GOF 3's chunk.
  source->bytes_read = 0;
  const auto gof = reader->ReadGof(3);
  ASSERT_TRUE(gof.ok());
  EXPECT_EQ(*gof, SampleGofs()[3]);
  EXPECT_EQ(source->bytes_read, reader->gofs()[4].offset - reader->gofs()[3].offset);
  EXPECT_EQ(source->bytes_read,
            kChunkHeaderSize + EncodeGofPayload(SampleGofs()[3]).size() + kChunkCrcSize);
}

TEST(FormatContainerTest, WithoutTrailerTheReaderScansAndFindsTheSameGofs) {
  std::vector<uint8_t> file = WriteSample();
  auto indexed = ContainerReader::OpenMemory(file);
  ASSERT_TRUE(indexed.ok());
  file.resize(file.size() - kTrailerChunkSize);  // drop TRLR: the index can't be found
  auto scanned = ContainerReader::OpenMemory(file, "cut.mvid");
  ASSERT_TRUE(scanned.ok());
  EXPECT_FALSE(scanned->used_index());
  EXPECT_EQ(scanned->index_status().code(), StatusCode::kCorrupt);
  EXPECT_EQ(scanned->gofs(), indexed->gofs());
  EXPECT_EQ(scanned->scan_status().message(),
            "cut.mvid: the file ends after 5 groups of frames without INDX/TRLR (truncated)");
  for (size_t k = 0; k < 5; ++k) EXPECT_EQ(*scanned->ReadGof(k), SampleGofs()[k]);
  EXPECT_EQ(*scanned->ReadBase(), Bytes("draco base mesh"));
}

TEST(FormatContainerTest, FileAndOstreamRoundTrip) {
  testing::TempDir dir;
  const std::string path = dir.File("sample.mvid");
  {
    std::ofstream out(path, std::ios::binary);
    ContainerWriter writer(OstreamSink(out, path));
    ASSERT_TRUE(writer.Begin(SampleHeader(0)).ok());  // frame_count unknown up front
    ASSERT_TRUE(writer.WriteGof(SampleGof(0, 4)).ok());
    ASSERT_TRUE(writer.Finish().ok());
  }
  auto reader = ContainerReader::OpenFile(path);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_TRUE(reader->used_index());
  EXPECT_FALSE(reader->has_base());
  EXPECT_EQ(reader->ReadBase().status().code(), StatusCode::kNotFound);
  EXPECT_EQ(*reader->ReadGof(0), SampleGof(0, 4));
  EXPECT_EQ(ContainerReader::OpenFile(dir.File("missing.mvid")).status().code(),
            StatusCode::kNotFound);
}

TEST(FormatContainerTest, StreamReaderDeliversChunksInOrder) {
  const std::vector<uint8_t> file = WriteSample();
  std::istringstream in(std::string(file.begin(), file.end()));
  StreamReader reader(in, "pipe", {.max_chunk_payload = 1 << 20, .read_step = 7});
  ASSERT_EQ(*reader.ReadHeader(), SampleHeader(18));
  auto item = reader.Next();
  ASSERT_TRUE(item.ok());
  EXPECT_EQ(item->kind, StreamItem::Kind::kBase);
  EXPECT_EQ(item->bytes, Bytes("draco base mesh"));
  item = reader.Next();
  EXPECT_EQ(item->kind, StreamItem::Kind::kMotion);
  EXPECT_EQ(item->bytes, Bytes("segments and weights"));
  for (const GroupOfFrames& expected : SampleGofs()) {
    item = reader.Next();
    ASSERT_TRUE(item.ok()) << item.status().ToString();
    ASSERT_EQ(item->kind, StreamItem::Kind::kGof);
    EXPECT_EQ(item->gof, expected);
  }
  item = reader.Next();
  ASSERT_EQ(item->kind, StreamItem::Kind::kIndex);
  EXPECT_EQ(item->index.gofs.size(), 5u);
  EXPECT_EQ(reader.Next()->kind, StreamItem::Kind::kEnd);
  EXPECT_EQ(reader.Next()->kind, StreamItem::Kind::kEnd);
  EXPECT_EQ(reader.offset(), file.size());
}

TEST(FormatContainerTest, WriterRejectsOutOfOrderCalls) {
  ContainerWriter writer([](std::span<const uint8_t>) { return Status::Ok(); });
  EXPECT_EQ(writer.WriteGof(SampleGof(0, 4)).message(),
            "ContainerWriter: WriteGof must come after Begin and before Finish");
  ContainerHeader bad = SampleHeader(0);
  bad.streams[0].codec = "hevc1";
  EXPECT_EQ(writer.Begin(bad).message(),
            "container header: stream 0 codec tag \"hevc1\" is not 4 characters");
  ASSERT_TRUE(writer.Begin(SampleHeader(8)).ok());
  EXPECT_EQ(writer.WriteGof(SampleGof(1, 4)).message(), "ContainerWriter: GOF 0 has gof_index 1");
  GroupOfFrames one_stream = SampleGof(0, 4);
  one_stream.packets.pop_back();
  EXPECT_EQ(writer.WriteGof(one_stream).message(),
            "ContainerWriter: GOF 0 has 1 packet lists for 2 streams");
  ASSERT_TRUE(writer.WriteGof(SampleGof(0, 4)).ok());
  // A BASE after a GOF starts key group 1; a second one before its GOFs is refused.
  ASSERT_TRUE(writer.WriteBase(Bytes("next")).ok());
  EXPECT_EQ(writer.key_group(), 1u);
  EXPECT_EQ(writer.WriteBase(Bytes("again")).message(),
            "ContainerWriter: WriteBase: a second BASE in key group 1 before any of its GOFs");
  EXPECT_EQ(writer.Finish().message(),
            "ContainerWriter: the header declared frame_count 8 but 4 frames were written");
}

TEST(FormatContainerTest, ValidateReportsChunksAndIndex) {
  const std::vector<uint8_t> file = WriteSample();
  const ValidationReport report = ValidateContainer(file, "sample.mvid");
  EXPECT_TRUE(report.ok()) << report.ToText();
  EXPECT_TRUE(report.header_ok);
  EXPECT_TRUE(report.has_index);
  EXPECT_TRUE(report.index_consistent);
  EXPECT_EQ(report.gof_count, 5u);
  EXPECT_EQ(report.frame_count, 18u);
  std::vector<std::string> types;
  for (const ChunkReport& chunk : report.chunks) {
    types.push_back(chunk.type);
    EXPECT_TRUE(chunk.crc_ok);
  }
  EXPECT_EQ(types, (std::vector<std::string>{"HEAD", "BASE", "MOTN", "GOF ", "GOF ", "GOF ",
                                             "GOF ", "GOF ", "INDX", "TRLR"}));
  EXPECT_EQ(report.chunks[0].offset, 8u);
  EXPECT_EQ(report.chunks[1].payload_size, 15u);
  EXPECT_TRUE(report.ToStatus().ok());

  // An index pointing at the wrong GOF: CRC-valid but inconsistent.
  std::vector<uint8_t> moved = file;
  const uint64_t index_offset = report.chunks[8].offset;
  const size_t entry0 = index_offset + kChunkHeaderSize + 28;
  moved[entry0] += 1;  // entry 0 offset off by one; re-seal the INDX CRC
  const size_t index_end = index_offset + kChunkHeaderSize + report.chunks[8].payload_size;
  ByteWriter crc;
  crc.PutU32(Crc32c(std::span<const uint8_t>(moved).subspan(index_offset, index_end - index_offset)));
  std::copy(crc.bytes().begin(), crc.bytes().end(), moved.begin() + index_end);
  const ValidationReport bad = ValidateContainer(moved, "moved.mvid");
  EXPECT_FALSE(bad.ok());
  EXPECT_TRUE(bad.has_index);
  EXPECT_FALSE(bad.index_consistent);
  ASSERT_EQ(bad.errors.size(), 1u);
  EXPECT_EQ(bad.errors[0], "moved.mvid: chunk 'INDX' at offset " + std::to_string(index_offset) +
                               ": entry 0 does not match the GOF chunk at " +
                               std::to_string(report.chunks[3].offset));
  EXPECT_EQ(bad.ToStatus().code(), StatusCode::kCorrupt);
}

// Three key groups: BASE+MOTN, 2 GOFs | BASE+MOTN, 1 GOF | BASE only, 2 GOFs (18 frames).
std::vector<uint8_t> WriteKeyGroups() {
  std::vector<uint8_t> file;
  ContainerWriter writer([&](std::span<const uint8_t> bytes) {
    file.insert(file.end(), bytes.begin(), bytes.end());
    return Status::Ok();
  });
  EXPECT_TRUE(writer.Begin(SampleHeader(18)).ok());
  const std::vector<GroupOfFrames> gofs = SampleGofs();
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(writer.WriteBase(Bytes("base " + std::to_string(k))).ok());
    if (k < 2) {
      EXPECT_TRUE(writer.WriteMotion(Bytes("motion " + std::to_string(k))).ok());
    }
    const uint32_t first = k == 0 ? 0 : k == 1 ? 2 : 3;
    const uint32_t end = k == 0 ? 2 : k == 1 ? 3 : 5;
    for (uint32_t g = first; g < end; ++g) EXPECT_TRUE(writer.WriteGof(gofs[g]).ok());
    EXPECT_EQ(writer.key_group(), static_cast<size_t>(k));
  }
  EXPECT_TRUE(writer.Finish().ok());
  return file;
}

TEST(FormatContainerTest, KeyGroupsAreIndexedScannedStreamedAndValidated) {
  const std::vector<uint8_t> file = WriteKeyGroups();
  const ValidationReport report = ValidateContainer(file, "keys.mvid");
  EXPECT_TRUE(report.ok()) << report.ToText();
  EXPECT_EQ(report.key_group_count, 3u);
  EXPECT_EQ(report.frame_count, 18u);

  auto expect_key_groups = [](ContainerReader& reader, size_t count) {
    ASSERT_EQ(reader.key_groups().size(), count);
    const std::vector<size_t> first_gof = {0, 2, 3};
    for (size_t k = 0; k < count; ++k) {
      EXPECT_EQ(reader.key_groups()[k].first_gof, first_gof[k]);
      const auto base = reader.ReadBase(k);
      ASSERT_TRUE(base.ok()) << base.status().message();
      EXPECT_EQ(*base, Bytes("base " + std::to_string(k)));
      EXPECT_EQ(reader.ReadMotion(k).ok(), k < 2);
    }
    EXPECT_EQ(reader.KeyGroupOfGof(0), 0u);
    EXPECT_EQ(reader.KeyGroupOfGof(1), 0u);
    EXPECT_EQ(reader.KeyGroupOfGof(2), 1u);
    if (count == 3) {
      EXPECT_EQ(reader.GofsOfKeyGroup(2), (std::pair<size_t, size_t>{3, 5}));
    }
  };
  auto indexed = ContainerReader::OpenMemory(file, "keys.mvid");
  ASSERT_TRUE(indexed.ok());
  EXPECT_TRUE(indexed->used_index());
  EXPECT_EQ(indexed->format_version(), 2u);
  expect_key_groups(*indexed, 3);

  // Cut inside the third key group's BASE: the scan offers the first two key groups whole.
  const size_t third_base = report.chunks[8].offset;
  ASSERT_EQ(report.chunks[8].type, "BASE");
  auto cut = ContainerReader::OpenMemory(
      std::vector<uint8_t>(file.begin(), file.begin() + third_base + 10), "cut.mvid");
  ASSERT_TRUE(cut.ok());
  EXPECT_FALSE(cut->used_index());
  expect_key_groups(*cut, 2);
  EXPECT_EQ(cut->frame_count(), 12u);

  // Streamed: every item names its key group.
  std::istringstream in(std::string(file.begin(), file.end()));
  StreamReader stream(in, "pipe");
  ASSERT_TRUE(stream.ReadHeader().ok());
  std::vector<std::pair<int, size_t>> items;
  while (true) {
    auto item = stream.Next();
    ASSERT_TRUE(item.ok()) << item.status().message();
    if (item->kind == StreamItem::Kind::kEnd) break;
    if (item->kind != StreamItem::Kind::kIndex) {
      items.push_back({static_cast<int>(item->kind), item->key_group});
    }
  }
  const int base = static_cast<int>(StreamItem::Kind::kBase);
  const int motion = static_cast<int>(StreamItem::Kind::kMotion);
  const int gof = static_cast<int>(StreamItem::Kind::kGof);
  EXPECT_EQ(items, (std::vector<std::pair<int, size_t>>{{base, 0}, {motion, 0}, {gof, 0},
                                                         {gof, 0}, {base, 1}, {motion, 1},
                                                         {gof, 1}, {base, 2}, {gof, 2},
                                                         {gof, 2}}));
}

TEST(FormatContainerTest, AKeyGroupWithoutGroupsOfFramesIsRefused) {
  ContainerWriter writer([](std::span<const uint8_t>) { return Status::Ok(); });
  ASSERT_TRUE(writer.Begin(SampleHeader(0)).ok());
  ASSERT_TRUE(writer.WriteBase(Bytes("b0")).ok());
  ASSERT_TRUE(writer.WriteGof(SampleGof(0, 4)).ok());
  ASSERT_TRUE(writer.WriteBase(Bytes("b1")).ok());
  EXPECT_EQ(writer.Finish().message(), "ContainerWriter: the last key group has no group of frames");
}

// The minimal file of the spec's annotated hex dump: one stream, one 2-frame GOF.
std::vector<uint8_t> MinimalFile() {
  std::vector<uint8_t> file;
  ContainerWriter writer([&](std::span<const uint8_t> bytes) {
    file.insert(file.end(), bytes.begin(), bytes.end());
    return Status::Ok();
  });
  ContainerHeader header;
  header.frame_rate_numerator = 30;
  header.frame_rate_denominator = 1;
  header.frame_count = 2;
  header.gof_size = 2;
  header.level_count = 1;
  header.streams = {{"hevc", 16, 8, 10, "disp"}};
  header.metadata_json = "{}";
  EXPECT_TRUE(writer.Begin(header).ok());
  EXPECT_TRUE(writer.WriteBase(Bytes("BM")).ok());
  EXPECT_TRUE(writer.WriteMotion(Bytes("MO")).ok());
  GroupOfFrames gof{0, 0, 2, Bytes("T"), {{Bytes("P0"), Bytes("P1")}}};
  EXPECT_TRUE(writer.WriteGof(gof).ok());
  EXPECT_TRUE(writer.Finish().ok());
  return file;
}

std::string HexDump(const std::vector<uint8_t>& bytes) {
  std::string text;
  for (size_t line = 0; line < bytes.size(); line += 16) {
    char buffer[24];
    std::snprintf(buffer, sizeof(buffer), "%04zx ", line);
    text += buffer;
    for (size_t i = line; i < line + 16 && i < bytes.size(); ++i) {
      std::snprintf(buffer, sizeof(buffer), " %02x", bytes[i]);
      text += buffer;
    }
    text += "\n";
  }
  return text;
}

TEST(FormatContainerTest, SpecHexDumpMatchesTheWriter) {
  const std::vector<uint8_t> file = MinimalFile();
  EXPECT_EQ(file.size(), 275u);
  EXPECT_TRUE(ValidateContainer(file).ok());
  const std::filesystem::path spec =
      std::filesystem::path(__FILE__).parent_path().parent_path() / "spec" / "mvid-container.md";
  if (!std::filesystem::exists(spec)) GTEST_SKIP() << "spec/mvid-container.md not beside tests/";
  const std::string text = testing::ReadFile(spec.string());
  EXPECT_NE(text.find("```\n" + HexDump(file) + "```"), std::string::npos)
      << "the spec's hex dump differs from what the writer produces:\n" << HexDump(file);
}

}  // namespace
}  // namespace meshvid
