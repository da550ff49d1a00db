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
  const uint64_t index_chunk = kChunkHeaderSize + 8 + 8 + 4 + 5 * 16 + kChunkCrcSize;
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
  EXPECT_EQ(writer.WriteBase(Bytes("late")).message(),
            "ContainerWriter: WriteBase must come after Begin and before any GOF");
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
  const size_t entry0 = index_offset + kChunkHeaderSize + 20;
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
    char buffer[8];
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
  EXPECT_EQ(file.size(), 267u);
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
