// Tests of the container's byte layer: CRC32C vectors and the bounds-checked ByteReader/Writer.
#include <gtest/gtest.h>

#include <numeric>
#include <string>
#include <vector>

#include "format/byte_io.h"
#include "format/crc32c.h"

namespace meshvid {
namespace {

TEST(FormatCrc32cTest, Rfc3720AndCheckVectors) {
  std::vector<uint8_t> zeros(32, 0x00), ones(32, 0xFF), ascending(32), descending(32);
  std::iota(ascending.begin(), ascending.end(), 0);
  for (int i = 0; i < 32; ++i) descending[i] = static_cast<uint8_t>(31 - i);
  EXPECT_EQ(Crc32c(zeros), 0x8A9136AAu);
  EXPECT_EQ(Crc32c(ones), 0x62A8AB43u);
  EXPECT_EQ(Crc32c(ascending), 0x46DD794Eu);
  EXPECT_EQ(Crc32c(descending), 0x113FDB5Cu);
  EXPECT_EQ(Crc32c(AsBytes("123456789")), 0xE3069283u);
  EXPECT_EQ(Crc32c({}), 0u);
}

TEST(FormatCrc32cTest, PortableAndHardwareAgreeAtEveryLengthAndSplit) {
  std::vector<uint8_t> data(300);
  for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<uint8_t>(i * 131 + 7);
  for (size_t length = 0; length <= data.size(); length += 7) {
    const std::span<const uint8_t> part(data.data(), length);
    const uint32_t whole = Crc32c(part);
    EXPECT_EQ(Crc32cExtendPortable(0, part), whole) << length;
    const size_t split = length / 3;
    EXPECT_EQ(Crc32cExtend(Crc32c(part.first(split)), part.subspan(split)), whole) << length;
  }
}

TEST(FormatByteIoTest, WriterIsLittleEndianAndReaderReadsItBack) {
  ByteWriter writer;
  writer.PutU8(0xAB);
  writer.PutU16(0x1234);
  writer.PutU32(0xDEADBEEF);
  writer.PutU64(0x0102030405060708ull);
  writer.PutFourcc("GOF");
  writer.PutSizedString("hi");
  const std::vector<uint8_t> expected = {0xAB, 0x34, 0x12, 0xEF, 0xBE, 0xAD, 0xDE, 0x08, 0x07,
                                         0x06, 0x05, 0x04, 0x03, 0x02, 0x01, 'G',  'O',  'F',
                                         ' ',  0x02, 0x00, 0x00, 0x00, 'h',  'i'};
  ASSERT_EQ(writer.bytes(), expected);

  ByteReader reader(writer.bytes(), "test");
  EXPECT_EQ(*reader.ReadU8("a"), 0xAB);
  EXPECT_EQ(*reader.ReadU16("b"), 0x1234);
  EXPECT_EQ(*reader.ReadU32("c"), 0xDEADBEEFu);
  EXPECT_EQ(*reader.ReadU64("d"), 0x0102030405060708ull);
  const auto fourcc = *reader.ReadBytes(4, "e");
  EXPECT_EQ(std::string(fourcc.begin(), fourcc.end()), "GOF ");
  EXPECT_EQ(*reader.ReadSizedString(10, "f"), "hi");
  EXPECT_EQ(reader.remaining(), 0u);
}

TEST(FormatByteIoTest, ReaderNeverReadsPastTheEnd) {
  const std::vector<uint8_t> three = {1, 2, 3};
  ByteReader reader(three, "tiny");
  const auto u32 = reader.ReadU32("frame_count");
  ASSERT_FALSE(u32.ok());
  EXPECT_EQ(u32.status().code(), StatusCode::kCorrupt);
  EXPECT_EQ(u32.status().message(),
            "tiny: truncated frame_count: needs 4 bytes at offset 0 but only 3 remain");
  EXPECT_EQ(reader.position(), 0u);  // a failed read consumes nothing
  EXPECT_EQ(*reader.ReadU16("x"), 0x0201);
  EXPECT_FALSE(reader.ReadU16("y").ok());
  EXPECT_FALSE(reader.ReadU64("z").ok());
  EXPECT_FALSE(reader.ReadBytes(~uint64_t{0}, "huge").ok());  // no overflow on absurd sizes
  EXPECT_FALSE(reader.Skip(2, "skip").ok());
  EXPECT_EQ(*reader.ReadU8("w"), 3);
  EXPECT_FALSE(reader.ReadU8("v").ok());
}

TEST(FormatByteIoTest, SizedStringRespectsLimitAndRemainingBytes) {
  ByteWriter writer;
  writer.PutSizedString("abcdef");
  ByteReader limited(writer.bytes(), "s");
  EXPECT_EQ(limited.ReadSizedString(5, "name").status().message(),
            "s: name size 6 exceeds the limit of 5 bytes");
  std::vector<uint8_t> lying = {0xFF, 0xFF, 0xFF, 0x7F, 'a'};
  ByteReader short_reader(lying, "s");
  EXPECT_EQ(short_reader.ReadSizedString(~uint64_t{0}, "name").status().message(),
            "s: truncated name: needs 2147483647 bytes at offset 4 but only 1 remain");
}

}  // namespace
}  // namespace meshvid
