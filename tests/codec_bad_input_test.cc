// Bad input for the codec payloads: counts far beyond what a group's bytes hold (with every
// CRC valid, so only the codec can catch them), and zstd frames that do not expand to the
// size their counts say. A clean kCorrupt error, never an abort, and no allocation larger
// than the input justifies.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "codec/common/compression.h"
#include "codec/dec/gof_side_info.h"
#include "codec/dec/motion_decoder.h"
#include "codec/dec/mvid_decoder.h"
#include "codec/dec/video_decoder.h"
#include "format/byte_io.h"
#include "format/chunk.h"
#include "format/crc32c.h"
#include "format/validate.h"
#include "tests/allocation_tracker.h"
#include "tests/mvid_mutants.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

const std::string kGolden = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v1.mvid";
/// Far below the gigabytes the corrupt counts below would ask for.
constexpr size_t kAllocationLimit = 4u << 20;

using testing::AllocationTracker;

std::vector<uint8_t> GoldenBytes() {
  const std::string text = testing::ReadFile(kGolden);
  return {text.begin(), text.end()};
}

/// The offset of the first chunk of `type` in `file` (0 if none).
size_t ChunkOffset(const std::vector<uint8_t>& file, std::string_view type) {
  for (const ChunkReport& chunk : ValidateContainer(file).chunks) {
    if (chunk.type == type) return chunk.offset;
  }
  return 0;
}

/// Rewrites the CRC of the chunk at `offset` after a deliberate edit of its payload.
void Reseal(std::vector<uint8_t>* file, size_t offset) {
  const size_t end = offset + kChunkHeaderSize + LoadLittleEndianU64(file->data() + offset + 8);
  const uint32_t crc = Crc32c(std::span<const uint8_t>(*file).subspan(offset, end - offset));
  for (int i = 0; i < 4; ++i) (*file)[end + i] = static_cast<uint8_t>(crc >> (8 * i));
}

/// A transform block: frame_count, segment_count, then `frame`.
std::vector<uint8_t> TransformBlock(uint32_t frames, uint32_t segments,
                                    std::span<const uint8_t> frame) {
  ByteWriter writer;
  writer.PutU32(frames);
  writer.PutU32(segments);
  writer.PutBytes(frame);
  return writer.Release();
}

/// A zstd frame of `blocks` RLE blocks of 128 KiB each (4 bytes each, 128 KiB out each).
std::vector<uint8_t> RleFrame(int blocks) {
  std::vector<uint8_t> frame = {0x28, 0xB5, 0x2F, 0xFD, 0x00, 0x38};
  for (int b = 0; b < blocks; ++b) {
    // Block_Header: Last_Block, Block_Type 1 = RLE, Block_Size 2^17; then the repeated byte.
    const uint32_t header = (b + 1 == blocks ? 1u : 0u) | (1u << 1) | ((128u * 1024u) << 3);
    for (int i = 0; i < 3; ++i) frame.push_back(static_cast<uint8_t>(header >> (8 * i)));
    frame.push_back(0);
  }
  return frame;
}

TEST(CodecBadInputTest, DecompressBlockKeepsExactSizesAndNamesEveryMismatch) {
  std::vector<uint8_t> raw(100000);
  for (size_t i = 0; i < raw.size(); ++i) raw[i] = static_cast<uint8_t>(i * i / 7);
  const std::vector<uint8_t> compressed = CompressBlock(raw);
  EXPECT_EQ(*DecompressBlock(compressed, raw.size(), "block"), raw);
  const std::vector<uint8_t> no_size = testing::ZstdFrameWithoutContentSize(raw);
  EXPECT_EQ(*DecompressBlock(no_size, raw.size(), "block"), raw);
  EXPECT_TRUE(DecompressBlock(CompressBlock({}), 0, "empty")->empty());

  EXPECT_EQ(DecompressBlock(compressed, raw.size() + 1, "block").status().ToString(),
            "corrupt: block: expands to 100000 bytes, expected 100001");
  EXPECT_EQ(DecompressBlock(no_size, raw.size() + 1, "block").status().ToString(),
            "corrupt: block: expands to 100000 bytes, expected 100001");
  EXPECT_EQ(DecompressBlock(no_size, raw.size() - 1, "block").status().ToString(),
            "corrupt: block: expands to more than 99999 bytes, expected 99999");
  const std::span<const uint8_t> cut = std::span(no_size).first(no_size.size() - 10);
  EXPECT_EQ(DecompressBlock(cut, raw.size(), "block").status().ToString(),
            "corrupt: block: the zstd frame is truncated (after 99990 of 100000 bytes)");
  std::vector<uint8_t> trailing = compressed;
  trailing.push_back(0);
  EXPECT_EQ(DecompressBlock(trailing, raw.size(), "block").status().ToString(),
            "corrupt: block: 1 bytes follow the zstd frame");
  EXPECT_EQ(DecompressBlock(raw, raw.size(), "block").status().ToString(),
            "corrupt: block: not a zstd frame");
}

TEST(CodecBadInputTest, DecompressBlockAllocatesOnlyWhatTheFrameCanHold) {
  // 40 bytes of frame can expand to at most 40 x 32768 bytes: a larger size is refused
  // before anything is allocated.
  const std::vector<uint8_t> small = testing::ZstdFrameWithoutContentSize(
      std::vector<uint8_t>(31, 7));
  ASSERT_EQ(small.size(), 40u);
  EXPECT_TRUE(ZstdCanExpandTo(40, 40 * kMaxZstdExpansion));
  EXPECT_FALSE(ZstdCanExpandTo(40, 40 * kMaxZstdExpansion + 1));
  EXPECT_FALSE(ZstdCanExpandTo(0, 1));
  EXPECT_FALSE(ZstdCanExpandTo(1, ~uint64_t{0}));
  {
    AllocationTracker tracker;
    const Status status = DecompressBlock(small, size_t{1} << 40, "huge").status();
    EXPECT_LT(tracker.largest(), 64u * 1024u);
    EXPECT_EQ(status.ToString(),
              "corrupt: huge: 40 compressed bytes cannot expand to the 1099511627776 bytes "
              "its counts say (a zstd frame expands at most 32768-fold)");
  }
  // 256 KiB of raw blocks could in principle expand to 8 GiB: the output still grows only
  // with the bytes the frame produces, so saying 4 GiB costs about 256 KiB.
  const std::vector<uint8_t> raw_blocks =
      testing::ZstdFrameWithoutContentSize(std::vector<uint8_t>(256 * 1024, 1));
  {
    AllocationTracker tracker;
    const Status status = DecompressBlock(raw_blocks, size_t{4} << 30, "lying").status();
    EXPECT_LT(tracker.largest(), 1u << 20);
    EXPECT_EQ(status.ToString(), "corrupt: lying: expands to 262144 bytes, expected 4294967296");
  }
  // A streaming decoder allocates the window a frame declares: up to 8 MiB is taken from any
  // frame, a larger window only when the expected size needs it.
  std::vector<uint8_t> windowed = testing::ZstdFrameWithoutContentSize(std::vector<uint8_t>(9));
  windowed[5] = 13 << 3;  // Window_Descriptor: 2^(10 + 13) bytes
  EXPECT_EQ(DecompressBlock(windowed, 9, "window")->size(), 9u);
  windowed[5] = 20 << 3;  // 2^30 bytes
  const Status too_large = DecompressBlock(windowed, 9, "window").status();
  EXPECT_EQ(too_large.code(), StatusCode::kCorrupt);
  EXPECT_NE(too_large.message().find("too much memory"), std::string::npos)
      << too_large.ToString();

  // RLE blocks are zstd's densest code (4 bytes for 128 KiB): such a frame is decoded as
  // long as it keeps within the expected size, and stops one byte past it.
  const std::vector<uint8_t> rle = RleFrame(16);
  EXPECT_EQ(DecompressBlock(rle, 16 * 128 * 1024, "rle")->size(), 16u * 128 * 1024);
  {
    AllocationTracker tracker;
    const Status status = DecompressBlock(rle, 3 * 128 * 1024, "rle").status();
    EXPECT_LE(tracker.largest(), 3u * 128 * 1024);
    EXPECT_EQ(status.ToString(), "corrupt: rle: expands to more than 393216 bytes, expected "
                                 "393216");
  }
}

TEST(CodecBadInputTest, HugeTransformCountsFailBeforeAllocating) {
  // Two frames of two segments, in a frame without a content size; the counts say more.
  std::vector<uint8_t> raw(2 * 2 * 24);
  for (size_t i = 0; i < raw.size(); ++i) raw[i] = static_cast<uint8_t>(i % 5);
  const std::vector<uint8_t> frame = testing::ZstdFrameWithoutContentSize(raw);
  const MotionQuantization quantization;
  ASSERT_TRUE(DecodeTransforms(TransformBlock(2, 2, frame), 2, 2, quantization).ok());
  for (const uint32_t frames : {3'000'000u, 0x7FFFFFFFu, 0xFFFFFFFFu}) {
    AllocationTracker tracker;
    const Status status =
        DecodeTransforms(TransformBlock(frames, 2, frame), frames, 2, quantization).status();
    EXPECT_LT(tracker.largest(), 64u * 1024u) << frames;
    EXPECT_EQ(status.ToString(), "corrupt: transforms: " + std::to_string(frames) +
                                     " frames x 2 segments need more transform bytes than " +
                                     std::to_string(frame.size()) + " coded bytes can hold");
  }
  // Counts whose byte size does not fit in 64 bits.
  const Status overflow =
      DecodeTransforms(TransformBlock(0xFFFFFFFFu, 0xFFFFFFFFu, frame), 0xFFFFFFFFu,
                       0xFFFFFFFFu, quantization)
          .status();
  EXPECT_EQ(overflow.code(), StatusCode::kCorrupt);
  EXPECT_NE(overflow.message().find("4294967295 frames x 4294967295 segments"),
            std::string::npos)
      << overflow.message();
}

TEST(CodecBadInputTest, GroupsClaimingHugeFrameCountsFailCleanlyWithBoundedMemory) {
  const std::vector<uint8_t> golden = GoldenBytes();
  // The counts a corruption sweep found aborting (bad_alloc) or taking gigabytes.
  for (const uint32_t frames : {3'000'000u, 0x7FFFFFFFu, 0xFFFFFFFFu}) {
    SCOPED_TRACE(frames);
    StatusOr<std::vector<uint8_t>> mutant = testing::WithHugeLastGroup(golden, frames);
    ASSERT_TRUE(mutant.ok()) << mutant.status().ToString();
    AllocationTracker tracker;
    StatusOr<std::unique_ptr<MvidDecoder>> decoder = MvidDecoder::OpenMemory(*mutant);
    if (!decoder.ok()) {
      EXPECT_EQ(decoder.status().code(), StatusCode::kCorrupt) << decoder.status().ToString();
      continue;
    }
    // The intact first group (frames 0..3) still decodes; the damaged one is an error. With
    // 2^32 - 1 frames the group's last frame number passes the largest u32: which frames the
    // container layer then calls readable is its business, the codec must only fail cleanly.
    const uint32_t readable = (*decoder)->info().frame_count;
    for (uint32_t frame = 0; frame < std::min(readable, 4u); ++frame) {
      const Status decoded = (*decoder)->DecodeFrame(frame, 2).status();
      EXPECT_TRUE(decoded.ok()) << frame << ": " << decoded.ToString();
    }
    const Status damaged = (*decoder)->DecodeFrame(4, 2).status();
    EXPECT_FALSE(damaged.ok());
    if (readable > 4) {
      EXPECT_EQ(damaged.code(), StatusCode::kCorrupt) << damaged.ToString();
      EXPECT_NE(damaged.message().find("coded bytes can hold"), std::string::npos)
          << damaged.ToString();
    }
    EXPECT_FALSE((*decoder)->DecodeTransforms(5).ok());
    EXPECT_LT(tracker.largest(), kAllocationLimit);
  }
}

TEST(CodecBadInputTest, SideInformationWithHugeCountsIsRejectedBeforeAllocating) {
  std::vector<uint8_t> raw(2 * 2 * 24, 0);
  const std::vector<uint8_t> frame = testing::ZstdFrameWithoutContentSize(raw);
  const std::vector<uint8_t> block = TransformBlock(0x7FFFFFFF, 2, frame);
  const std::vector<uint8_t> side = EncodeGofSideInfo(DisplacementPacking::kLatticeOrder,
                                                      DisplacementRange{0.0f, 1.0f}, {}, block);
  AllocationTracker tracker;
  const Status status = DecodeGofSideInfo(side, 0x7FFFFFFF, 2, MotionQuantization{}).status();
  EXPECT_LT(tracker.largest(), 64u * 1024u);
  EXPECT_EQ(status.code(), StatusCode::kCorrupt);
  EXPECT_NE(status.message().find("2147483647 frames x 2 segments"), std::string::npos)
      << status.ToString();
}

TEST(CodecBadInputTest, SideInformationOfAnUnknownVersionIsUnsupported) {
  std::vector<uint8_t> side = EncodeGofSideInfo(DisplacementPacking::kLatticeOrder,
                                                DisplacementRange{0.0f, 1.0f}, {}, {});
  ASSERT_EQ(side[0], 2);  // what encoders write (spec/mvid-codec.md 2.4)
  side[0] = 3;
  const Status status = DecodeGofSideInfo(side, 1, 1, MotionQuantization{}).status();
  EXPECT_EQ(status.ToString(), "unsupported: group side information version 3 is not supported "
                               "(this decoder reads versions 1 and 2)");
}

TEST(CodecBadInputTest, ACutInsideBaseSaysTheBaseIsCut) {
  std::vector<uint8_t> file = GoldenBytes();
  const size_t base = ChunkOffset(file, "BASE");
  ASSERT_GT(base, 0u);
  file.resize(base + kChunkHeaderSize + 10);
  const Status status = MvidDecoder::OpenMemory(file).status();
  EXPECT_EQ(status.code(), StatusCode::kCorrupt);
  EXPECT_NE(status.message().find("key group 0's BASE chunk is cut or damaged (the chunk scan "
                                  "stopped: <memory>: chunk 'BASE' at offset " +
                                  std::to_string(base) + ": payload_size"),
            std::string::npos)
      << status.ToString();
  EXPECT_EQ(status.message().find("has no"), std::string::npos) << status.ToString();
}

TEST(CodecBadInputTest, PayloadDecoderErrorsNameTheFileAndGroup) {
  // Group 1's side information gets an unknown displacement_packing (CRC resealed): the
  // error must say which file and group, not only "group side information".
  std::vector<uint8_t> file = GoldenBytes();
  std::vector<size_t> gofs;
  for (const ChunkReport& chunk : ValidateContainer(file).chunks) {
    if (chunk.type == "GOF ") gofs.push_back(chunk.offset);
  }
  ASSERT_GE(gofs.size(), 2u);
  // GOF payload: gof_index, first_frame, frame_count, transforms_size; then the side
  // information: side_info_version, displacement_packing.
  file[gofs[1] + kChunkHeaderSize + 16 + 1] = 7;
  Reseal(&file, gofs[1]);
  testing::TempDir dir;
  const std::string path = dir.File("packing.mvid");
  testing::WriteFile(path, std::string(file.begin(), file.end()));
  StatusOr<std::unique_ptr<MvidDecoder>> decoder = MvidDecoder::OpenFile(path);
  ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
  EXPECT_TRUE((*decoder)->DecodeFrame(0, 1).ok());
  const Status damaged = (*decoder)->DecodeFrame(4, 1).status();
  EXPECT_EQ(damaged.ToString(), "corrupt: " + path + ": group 1: group side information: "
                                "unknown displacement_packing 7");
}

TEST(CodecBadInputTest, AVideoConfigurationTheDecoderRefusesIsCorruptData) {
  // FFV1 parses its configuration record (with a CRC) when opening: garbage is damaged data
  // from the file, not an internal error.
  const std::vector<uint8_t> garbage = {3, 0x55, 0xAA, 0x55, 0xAA, 1, 2, 3, 4, 5, 6, 7, 8,
                                        9, 10, 11, 12, 13, 14, 15};
  const Status ffv1 = VideoDecoder::Create(VideoCodec::kFfv1, 64, 64, garbage, 1).status();
  EXPECT_EQ(ffv1.code(), StatusCode::kCorrupt) << ffv1.ToString();
  EXPECT_NE(ffv1.message().find("ffv1 decoder refuses the 20-byte video configuration"),
            std::string::npos)
      << ffv1.ToString();
  EXPECT_TRUE(VideoDecoder::Create(VideoCodec::kFfv1, 64, 64, {}, 1).ok());
}

TEST(CodecBadInputTest, HeaderFrameCountIsCheckedAgainstTheGroups) {
  // HEAD claims 2^31 frames; the index and the groups hold 6. The index is not trusted, the
  // scan finds the 6 frames and the decoder reports both counts; validation fails.
  const std::vector<uint8_t> file = testing::WithHeaderFrameCount(GoldenBytes(), 0x80000000u);
  // Partial files are refused unless allowed.
  const StatusOr<std::unique_ptr<MvidDecoder>> refused = MvidDecoder::OpenMemory(file);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), StatusCode::kCorrupt);
  EXPECT_NE(refused.status().message().find(
                "partial file: only 6 of the 2147483648 frames its header promises are readable"),
            std::string::npos)
      << refused.status().ToString();
  StatusOr<std::unique_ptr<MvidDecoder>> decoder =
      MvidDecoder::OpenMemory(file, {.allow_partial = true});
  ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
  EXPECT_TRUE((*decoder)->info().partial());
  EXPECT_EQ((*decoder)->info().frame_count, 6u);
  EXPECT_EQ((*decoder)->info().declared_frame_count, 0x80000000u);
  EXPECT_FALSE((*decoder)->info().indexed);
  const ValidationReport report = ValidateContainer(file);
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.errors.back().find("HEAD declares frame_count 2147483648 but the GOFs hold 6"),
            std::string::npos)
      << report.ToText();
  EXPECT_EQ((*decoder)->DecodeFrame(6, 0).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace meshvid
