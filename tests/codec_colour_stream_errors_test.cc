// A colour stream that breaks the spec (spec/mvid-codec.md, "Colour video") is an error that
// says what is wrong, on opening for HEAD and on asking for the colours for a GOF; the
// geometry of a GOF whose colour packets are broken still decodes.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "codec/dec/mvid_decoder.h"
#include "format/container_reader.h"
#include "format/container_writer.h"

namespace meshvid {
namespace {

const std::string kGolden = std::string(MESHVID_GOLDEN_DIR) + "/sphere.colour.mvid";

/// The golden colour file re-wrapped with its HEAD and its first GOF changed as the edits say
/// (CRCs stay valid, so only the decoder's checks can catch the change).
std::vector<std::uint8_t> Rewrap(const std::function<void(ContainerHeader*)>& edit_header,
                                 const std::function<void(GroupOfFrames*)>& edit_first_gof) {
  auto reader = ContainerReader::OpenFile(kGolden);
  EXPECT_TRUE(reader.ok()) << reader.status().ToString();
  if (!reader.ok()) return {};
  std::vector<std::uint8_t> out;
  ContainerWriter writer([&out](std::span<const std::uint8_t> b) {
    out.insert(out.end(), b.begin(), b.end());
    return Status::Ok();
  });
  ContainerHeader header = reader->header();
  edit_header(&header);
  EXPECT_TRUE(writer.Begin(header).ok());
  EXPECT_TRUE(writer.WriteBase(*reader->ReadBase()).ok());
  EXPECT_TRUE(writer.WriteMotion(*reader->ReadMotion()).ok());
  for (std::size_t k = 0; k < reader->gof_count(); ++k) {
    GroupOfFrames gof = *reader->ReadGof(k);
    if (k == 0) edit_first_gof(&gof);
    const Status written = writer.WriteGof(gof);
    EXPECT_TRUE(written.ok()) << written.ToString();
  }
  EXPECT_TRUE(writer.Finish().ok());
  return out;
}

std::vector<std::uint8_t> WithHeader(const std::function<void(ContainerHeader*)>& edit) {
  return Rewrap(edit, [](GroupOfFrames*) {});
}

std::vector<std::uint8_t> WithFirstGof(const std::function<void(GroupOfFrames*)>& edit) {
  return Rewrap([](ContainerHeader*) {}, edit);
}

/// Opening `bytes` fails with `code` and a message holding `words`.
void ExpectOpenFails(std::vector<std::uint8_t> bytes, StatusCode code, const std::string& words) {
  auto decoder = MvidDecoder::OpenMemory(std::move(bytes));
  ASSERT_FALSE(decoder.ok());
  EXPECT_EQ(decoder.status().code(), code) << decoder.status().ToString();
  EXPECT_NE(decoder.status().ToString().find(words), std::string::npos)
      << decoder.status().ToString();
}

TEST(ColourStreamErrorsTest, AHeadWhoseSecondStreamIsNotEightBitColourIsUnsupported) {
  ExpectOpenFails(WithHeader([](ContainerHeader* h) { h->streams[1].bit_depth = 10; }),
                  StatusCode::kUnsupported, "not an 8-bit colour stream");
  ExpectOpenFails(WithHeader([](ContainerHeader* h) { h->streams[1].name = "alpha"; }),
                  StatusCode::kUnsupported, "not an 8-bit colour stream");
}

TEST(ColourStreamErrorsTest, AHeadWhoseColourPicturesDifferFromTheDisplacementsIsCorrupt) {
  const std::string words = "codec or picture size differs";
  ExpectOpenFails(WithHeader([](ContainerHeader* h) { h->streams[1].width += 8; }),
                  StatusCode::kCorrupt, words);
  ExpectOpenFails(WithHeader([](ContainerHeader* h) { h->streams[1].height += 8; }),
                  StatusCode::kCorrupt, words);
  ExpectOpenFails(WithHeader([](ContainerHeader* h) { h->streams[1].codec = "hevc"; }),
                  StatusCode::kCorrupt, words);
}

/// Frame 0 (in the broken first GOF) gives its positions but its colours fail with a message
/// holding `words`; the frames of the other GOFs decode whole.
void ExpectColoursOfTheFirstGofFail(std::vector<std::uint8_t> bytes, const std::string& words) {
  auto decoder = MvidDecoder::OpenMemory(std::move(bytes));
  ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
  std::vector<Eigen::Vector3f> positions;
  ASSERT_TRUE((*decoder)->DecodePositions(0, 2, &positions).ok());
  EXPECT_FALSE(positions.empty());
  std::vector<Colour> colours;
  for (int attempt = 0; attempt < 2; ++attempt) {  // asked again, the same error
    const Status status = (*decoder)->DecodeColours(0, 2, &colours);
    EXPECT_EQ(status.code(), StatusCode::kCorrupt) << status.ToString();
    EXPECT_NE(status.ToString().find(words), std::string::npos) << status.ToString();
  }
  EXPECT_FALSE((*decoder)->DecodeFrame(0, 2).ok());
  const std::uint32_t last = (*decoder)->info().frame_count - 1;
  auto mesh = (*decoder)->DecodeFrame(last, 2);
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->colours.size(), mesh->vertex_count());
}

TEST(ColourStreamErrorsTest, AGofWithTooFewOrTooManyColourPicturesIsCorrupt) {
  ExpectColoursOfTheFirstGofFail(WithFirstGof([](GroupOfFrames* g) { g->packets[1].clear(); }),
                                 "the colour video gives 0 pictures");
  ExpectColoursOfTheFirstGofFail(
      WithFirstGof([](GroupOfFrames* g) { g->packets[1].pop_back(); }), "the colour video gives");
  ExpectColoursOfTheFirstGofFail(WithFirstGof([](GroupOfFrames* g) {
                                   g->packets[1].push_back(g->packets[1].back());
                                 }),
                                 "the colour video gives");
}

TEST(ColourStreamErrorsTest, ColourPacketsThatDoNotDecodeAreCorrupt) {
  ExpectColoursOfTheFirstGofFail(WithFirstGof([](GroupOfFrames* g) {
                                   for (auto& packet : g->packets[1]) {
                                     packet.assign(packet.size(), 0x5A);
                                   }
                                 }),
                                 "colour");
}

}  // namespace
}  // namespace meshvid
