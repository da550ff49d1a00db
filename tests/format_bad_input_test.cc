// Bad input for every .mvid reader: truncation at every byte, every single-bit flip, wrong
// magic or version, absurd sizes and counts. No crash, a clear error, no big allocation, and
// every complete group of frames before a cut.
#include <gtest/gtest.h>

#include <sstream>

#include "format/byte_io.h"
#include "format/chunk.h"
#include "format/container_reader.h"
#include "format/container_writer.h"
#include "format/crc32c.h"
#include "format/stream_reader.h"
#include "format/validate.h"
#include "tests/allocation_tracker.h"

namespace meshvid {
namespace {

std::vector<uint8_t> Bytes(const std::string& text) { return {text.begin(), text.end()}; }

GroupOfFrames Gof(uint32_t k) {
  return {k, 2 * k, 2, Bytes("T" + std::to_string(k)),
          {{Bytes("key" + std::to_string(k)), Bytes("p" + std::to_string(k))}}};
}

// A small complete file: HEAD, BASE, MOTN, 3 GOFs, INDX, TRLR.
std::vector<uint8_t> SmallFile() {
  std::vector<uint8_t> file;
  ContainerWriter writer([&](std::span<const uint8_t> bytes) {
    file.insert(file.end(), bytes.begin(), bytes.end());
    return Status::Ok();
  });
  ContainerHeader header;
  header.frame_count = 6;
  header.gof_size = 2;
  header.streams = {{"av01", 8, 8, 10, "d"}};
  header.metadata_json = "{}";
  EXPECT_TRUE(writer.Begin(header).ok());
  EXPECT_TRUE(writer.WriteBase(Bytes("base")).ok());
  EXPECT_TRUE(writer.WriteMotion(Bytes("motion")).ok());
  for (uint32_t k = 0; k < 3; ++k) EXPECT_TRUE(writer.WriteGof(Gof(k)).ok());
  EXPECT_TRUE(writer.Finish().ok());
  return file;
}

// End offsets of the GOF chunks of SmallFile().
std::vector<uint64_t> GofEnds(const std::vector<uint8_t>& file) {
  std::vector<uint64_t> ends;
  for (const ChunkReport& chunk : ValidateContainer(file).chunks) {
    if (chunk.type == "GOF ") ends.push_back(chunk.offset + chunk.payload_size + 20);
  }
  return ends;
}

// Rewrites the crc32c of the chunk at `offset` so a deliberate edit passes the CRC.
void Reseal(std::vector<uint8_t>* file, size_t offset) {
  const uint64_t payload = LoadLittleEndianU64(file->data() + offset + 8);
  const size_t end = offset + kChunkHeaderSize + payload;
  ByteWriter crc;
  crc.PutU32(Crc32c(std::span<const uint8_t>(*file).subspan(offset, end - offset)));
  std::copy(crc.bytes().begin(), crc.bytes().end(), file->begin() + end);
}

TEST(FormatBadInputTest, TruncationAtEveryOffsetKeepsCompleteGofs) {
  const std::vector<uint8_t> file = SmallFile();
  const std::vector<uint64_t> gof_ends = GofEnds(file);
  ASSERT_EQ(gof_ends.size(), 3u);
  for (size_t cut = 0; cut < file.size(); ++cut) {
    const std::vector<uint8_t> prefix(file.begin(), file.begin() + cut);
    size_t complete = 0;
    while (complete < gof_ends.size() && gof_ends[complete] <= cut) ++complete;

    auto reader = ContainerReader::OpenMemory(prefix, "cut.mvid");
    if (reader.ok()) {
      EXPECT_FALSE(reader->used_index()) << cut;
      EXPECT_FALSE(reader->scan_status().ok()) << cut;
      ASSERT_EQ(reader->gof_count(), complete) << cut;
      for (size_t k = 0; k < complete; ++k) EXPECT_EQ(*reader->ReadGof(k), Gof(k)) << cut;
    } else {
      EXPECT_EQ(reader.status().code(), StatusCode::kCorrupt) << cut;
      EXPECT_EQ(complete, 0u) << cut;
    }

    std::istringstream in(std::string(prefix.begin(), prefix.end()));
    StreamReader stream(in, "pipe");
    size_t streamed = 0;
    if (stream.ReadHeader().ok()) {
      while (true) {
        auto item = stream.Next();
        if (!item.ok()) {
          EXPECT_EQ(item.status().code(), StatusCode::kCorrupt) << cut;
          EXPECT_NE(item.status().message().find("truncated"), std::string::npos)
              << cut << ": " << item.status().message();
          break;
        }
        ASSERT_NE(item->kind, StreamItem::Kind::kEnd) << cut;
        if (item->kind == StreamItem::Kind::kGof) {
          EXPECT_EQ(item->gof, Gof(streamed++)) << cut;
        }
      }
    }
    EXPECT_EQ(streamed, complete) << cut;

    const ValidationReport report = ValidateContainer(prefix);
    EXPECT_FALSE(report.ok()) << cut;
  }
}

TEST(FormatBadInputTest, EverySingleBitFlipIsDetected) {
  const std::vector<uint8_t> file = SmallFile();
  for (size_t bit = 0; bit < file.size() * 8; ++bit) {
    std::vector<uint8_t> flipped = file;
    flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    EXPECT_FALSE(ValidateContainer(flipped).ok()) << "bit " << bit;

    // The seekable reader never returns wrong data: whatever it returns equals the original.
    auto reader = ContainerReader::OpenMemory(flipped);
    if (!reader.ok()) continue;
    EXPECT_EQ(reader->header().streams.size(), 1u);
    if (auto base = reader->ReadBase(); base.ok()) {
      EXPECT_EQ(*base, Bytes("base")) << bit;
    }
    if (auto motion = reader->ReadMotion(); motion.ok()) {
      EXPECT_EQ(*motion, Bytes("motion"));
    }
    for (size_t k = 0; k < reader->gof_count(); ++k) {
      if (auto gof = reader->ReadGof(k); gof.ok()) {
        EXPECT_EQ(*gof, Gof(k)) << "bit " << bit;
      }
    }
  }
}

TEST(FormatBadInputTest, WrongMagicAndVersionAreNamed) {
  std::vector<uint8_t> file = SmallFile();
  file[0] = 'X';
  EXPECT_EQ(ContainerReader::OpenMemory(file, "a.mvid").status().ToString(),
            "corrupt: a.mvid: not a .mvid file (the first 4 bytes are not \"MVID\")");
  file = SmallFile();
  file[4] = 3;
  const Status version = ContainerReader::OpenMemory(file, "a.mvid").status();
  EXPECT_EQ(version.code(), StatusCode::kUnsupported);
  EXPECT_EQ(version.message(),
            "a.mvid: .mvid format_version 3 is not supported (this build reads versions 1 to 2)");
  std::istringstream in(std::string(file.begin(), file.end()));
  EXPECT_EQ(StreamReader(in, "pipe").ReadHeader().status().code(), StatusCode::kUnsupported);
  EXPECT_EQ(ValidateContainer(std::vector<uint8_t>{'M', 'V'}, "b").errors.at(0),
            "b: too short for a .mvid file (2 bytes; the preamble alone is 8)");
}

TEST(FormatBadInputTest, AbsurdSizesFailWithoutBigAllocations) {
  const std::vector<uint8_t> original = SmallFile();
  // HEAD payload_size = 2^60.
  std::vector<uint8_t> file = original;
  for (int i = 0; i < 8; ++i) file[16 + i] = i == 7 ? 0x10 : 0;
  testing::AllocationTracker tracker;
  const Status open = ContainerReader::OpenMemory(file, "big.mvid").status();
  const ValidationReport report = ValidateContainer(file, "big.mvid");
  std::istringstream in(std::string(file.begin(), file.end()));
  const Status streamed = StreamReader(in, "pipe").ReadHeader().status();
  // A stream limit above the claimed size: bounded steps, fails at the end of the stream.
  std::istringstream in2(std::string(file.begin(), file.end()));
  const Status stepped =
      StreamReader(in2, "pipe", {.max_chunk_payload = ~uint64_t{0}, .read_step = 4096})
          .ReadHeader().status();
  tracker.Stop();
  EXPECT_LT(tracker.largest(), 64u * 1024u);
  EXPECT_EQ(open.message(), "big.mvid: chunk 'HEAD' at offset 8: payload_size "
                            "1152921504606846976 exceeds the " +
                                std::to_string(original.size() - 28) +
                                " bytes the input can hold (truncated or corrupt file)");
  EXPECT_FALSE(report.ok());
  EXPECT_EQ(streamed.code(), StatusCode::kCorrupt);
  EXPECT_EQ(stepped.code(), StatusCode::kCorrupt);
  EXPECT_NE(stepped.message().find("stream ends at offset"), std::string::npos);
}

TEST(FormatBadInputTest, AbsurdCountsWithValidCrcFailWithoutBigAllocations) {
  // HEAD stream_count = 0xFFFFFFFF, CRC resealed so only the count check can catch it.
  std::vector<uint8_t> file = SmallFile();
  const size_t stream_count_at = kPreambleSize + kChunkHeaderSize + 20;
  for (int i = 0; i < 4; ++i) file[stream_count_at + i] = 0xFF;
  Reseal(&file, kPreambleSize);
  testing::AllocationTracker tracker;
  const Status open = ContainerReader::OpenMemory(file, "n.mvid").status();
  tracker.Stop();
  EXPECT_LT(tracker.largest(), 64u * 1024u);
  EXPECT_EQ(open.message(), "n.mvid: chunk 'HEAD' at offset 8: stream_count 4294967295 "
                            "exceeds the limit of 64");

  // GOF 1 packet_count = 0x7FFFFFFF with a resealed CRC.
  file = SmallFile();
  const ValidationReport layout = ValidateContainer(file);
  const size_t gof1 = layout.chunks[4].offset;
  const size_t packet_count_at = gof1 + kChunkHeaderSize + 12 + 4 + 2 + 4;  // after "T1"
  ASSERT_EQ(LoadLittleEndianU32(file.data() + packet_count_at), 2u);
  file[packet_count_at + 3] = 0x7F;
  Reseal(&file, gof1);
  auto reader = ContainerReader::OpenMemory(file, "n.mvid");
  ASSERT_TRUE(reader.ok());
  EXPECT_TRUE(reader->used_index());
  testing::AllocationTracker gof_tracker;
  const Status gof = reader->ReadGof(1).status();
  gof_tracker.Stop();
  EXPECT_LT(gof_tracker.largest(), 64u * 1024u);
  EXPECT_EQ(gof.message(), "n.mvid: chunk 'GOF ' at offset " + std::to_string(gof1) +
                               ": packet_count 2130706434 is more than the remaining bytes can "
                               "hold (at most 3)");
  EXPECT_EQ(*reader->ReadGof(2), Gof(2));  // the other groups stay readable
  EXPECT_FALSE(ValidateContainer(file).ok());
}

TEST(FormatBadInputTest, FrameRateZeroIsCorrupt) {
  // HEAD frame_rate_numerator = 0 with a resealed CRC: 0 fps used to pass --check.
  std::vector<uint8_t> file = SmallFile();
  const size_t numerator_at = kPreambleSize + kChunkHeaderSize;
  for (int i = 0; i < 4; ++i) file[numerator_at + i] = 0;
  Reseal(&file, kPreambleSize);
  EXPECT_EQ(ContainerReader::OpenMemory(file, "z.mvid").status().ToString(),
            "corrupt: z.mvid: chunk 'HEAD' at offset 8: frame_rate_numerator is 0 (0 fps)");
  const ValidationReport report = ValidateContainer(file, "z.mvid");
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.errors[0].find("frame_rate_numerator is 0"), std::string::npos);
  ContainerHeader header;
  header.frame_rate_numerator = 0;
  EXPECT_EQ(CheckHeader(header).code(), StatusCode::kInvalidArgument);
}

TEST(FormatBadInputTest, FrameRangesPastTheLastFrameNumberAreCorrupt) {
  // A group whose first_frame + frame_count passes 2^32 - 1 (GOF chunk and index entry): the
  // frame count of the file would wrap a u32.
  GroupOfFrames gof = Gof(0);
  gof.first_frame = 5;
  gof.frame_count = 0xFFFFFFFFu;
  StatusOr<GroupOfFrames> decoded = DecodeGofPayload(EncodeGofPayload(gof), 1, "g");
  EXPECT_EQ(decoded.status().ToString(),
            "corrupt: g: first_frame 5 + frame_count 4294967295 passes the last frame number");
  gof.first_frame = 0;
  gof.frame_count = 0xFFFFFFFFu;  // ends exactly at the limit
  EXPECT_TRUE(DecodeGofPayload(EncodeGofPayload(gof), 1, "g").ok());

  ContainerIndex index;
  index.key_groups = {{100, 200, 0}};
  index.gofs = {{300, 0, 4}, {400, 4, 0xFFFFFFFCu}};
  StatusOr<std::vector<uint8_t>> bytes = EncodeIndexPayload(index, 2);
  ASSERT_TRUE(bytes.ok());
  EXPECT_EQ(DecodeIndexPayload(*bytes, 2, "i").status().ToString(),
            "corrupt: i: entry 1 first_frame 4 + frame_count 4294967292 passes the last frame "
            "number");
  index.gofs[1].frame_count = 0xFFFFFFFBu;
  EXPECT_TRUE(DecodeIndexPayload(*EncodeIndexPayload(index, 2), 2, "i").ok());

  // GOF 2 of a file claims 2^32 - 1 frames (CRC resealed): reading it through the index
  // fails; with the file cut after it, the forward scan stops before it. The first two groups
  // stay readable either way.
  std::vector<uint8_t> file = SmallFile();
  const ChunkReport gof2_chunk = ValidateContainer(file).chunks[5];
  const size_t gof2 = gof2_chunk.offset;
  for (int i = 0; i < 4; ++i) file[gof2 + kChunkHeaderSize + 8 + i] = 0xFF;
  Reseal(&file, gof2);
  StatusOr<ContainerReader> indexed = ContainerReader::OpenMemory(file, "w.mvid");
  ASSERT_TRUE(indexed.ok());
  EXPECT_NE(indexed->ReadGof(2).status().message().find("passes the last frame number"),
            std::string::npos);
  EXPECT_EQ(*indexed->ReadGof(1), Gof(1));
  file.resize(gof2 + kChunkHeaderSize + gof2_chunk.payload_size + kChunkCrcSize);
  StatusOr<ContainerReader> reader = ContainerReader::OpenMemory(file, "w.mvid");
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_FALSE(reader->used_index());
  EXPECT_EQ(reader->frame_count(), 4u);
  EXPECT_NE(reader->scan_status().message().find("frame_count 4294967295 break the GOF sequence"),
            std::string::npos)
      << reader->scan_status().ToString();
}

TEST(FormatBadInputTest, UnknownChunksAreSkippedOnlyWhenFlagged) {
  std::vector<uint8_t> file = SmallFile();
  const size_t base_at = ValidateContainer(file).chunks[1].offset;
  // Insert an unknown chunk right after HEAD (before BASE), skippable: still valid to read.
  std::vector<uint8_t> extra = EncodeChunk(Fourcc("XTRA"), kChunkFlagSkippable, Bytes("?"));
  std::vector<uint8_t> skippable = file;
  skippable.insert(skippable.begin() + base_at, extra.begin(), extra.end());
  std::istringstream in(std::string(skippable.begin(), skippable.end()));
  StreamReader stream(in, "pipe");
  ASSERT_TRUE(stream.ReadHeader().ok());
  EXPECT_EQ(stream.Next()->kind, StreamItem::Kind::kBase);
  // Offsets after the insertion moved, so the index is now wrong: the reader scans instead.
  auto reader = ContainerReader::OpenMemory(skippable);
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ(reader->gof_count(), 3u);
  EXPECT_EQ(*reader->ReadGof(2), Gof(2));

  extra = EncodeChunk(Fourcc("XTRA"), 0, Bytes("?"));
  std::vector<uint8_t> required = file;
  required.insert(required.begin() + base_at, extra.begin(), extra.end());
  std::istringstream in2(std::string(required.begin(), required.end()));
  StreamReader strict(in2, "pipe");
  ASSERT_TRUE(strict.ReadHeader().ok());
  EXPECT_EQ(strict.Next().status().ToString(),
            "unsupported: pipe: chunk 'XTRA' at offset " + std::to_string(base_at) +
                ": unknown chunk type that is not skippable");
}

}  // namespace
}  // namespace meshvid
