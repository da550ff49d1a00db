// The colour video coder: 8-bit Y Cb Cr 4:4:4 pictures through FFV1 (lossless), HEVC and AV1
// (lossy), every group on its own, and pictures of the wrong format refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>

#include "codec/dec/video_decoder.h"
#include "codec/enc/coding/video_encoder.h"

namespace meshvid {
namespace {

constexpr int kWidth = 64, kHeight = 48, kFrames = 16, kGroup = 8;

/// Smooth patterns moving over time, a different one in each plane.
ColourPicture MakePicture(int t) {
  ColourPicture p{kWidth, kHeight, t, {}};
  for (int plane = 0; plane < 3; ++plane) {
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        const double v =
            128 + 90 * std::sin((0.1 + 0.05 * plane) * x + 0.1 * t) * std::cos(0.15 * y - 0.05 * t);
        p.planes[plane].push_back(static_cast<std::uint8_t>(std::lround(v)));
      }
    }
  }
  return p;
}

struct Coded {
  std::vector<std::uint8_t> extradata;
  std::vector<VideoPacket> packets;
  std::size_t bytes = 0;
};

VideoEncoding ColourSettings(VideoCodec codec, int qp) {
  VideoEncoding settings;
  settings.codec = codec;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.qp = qp;
  settings.threads = 1;
  settings.format = PictureFormat::kColour8;
  return settings;
}

Coded EncodeAll(VideoCodec codec, int qp) {
  auto encoder = VideoEncoder::Create(ColourSettings(codec, qp));
  EXPECT_TRUE(encoder.ok()) << encoder.status().ToString();
  Coded coded;
  if (!encoder.ok()) return coded;
  for (int t = 0; t < kFrames; ++t) {
    const Status status = (*encoder)->Encode(MakePicture(t), t % kGroup == 0, &coded.packets);
    EXPECT_TRUE(status.ok()) << status.ToString();
  }
  EXPECT_TRUE((*encoder)->Flush(&coded.packets).ok());
  coded.extradata = (*encoder)->extradata();
  for (const auto& p : coded.packets) coded.bytes += p.data.size();
  return coded;
}

std::map<std::int64_t, ColourPicture> Decode(VideoCodec codec, const Coded& coded, int first,
                                             int last) {
  auto decoder =
      VideoDecoder::Create(codec, kWidth, kHeight, coded.extradata, 1, PictureFormat::kColour8);
  EXPECT_TRUE(decoder.ok()) << decoder.status().ToString();
  std::vector<ColourPicture> pictures;
  for (const auto& packet : coded.packets) {
    if (packet.pts < first || packet.pts >= last) continue;
    const Status status = (*decoder)->Decode(packet, &pictures);
    EXPECT_TRUE(status.ok()) << status.ToString();
  }
  EXPECT_TRUE((*decoder)->Flush(&pictures).ok());
  std::map<std::int64_t, ColourPicture> by_pts;
  for (auto& p : pictures) by_pts[p.pts] = std::move(p);
  return by_pts;
}

double MeanError(const ColourPicture& a, const ColourPicture& b) {
  double sum = 0;
  for (int plane = 0; plane < 3; ++plane) {
    for (std::size_t i = 0; i < a.planes[plane].size(); ++i) {
      sum += std::abs(int(a.planes[plane][i]) - int(b.planes[plane][i]));
    }
  }
  return sum / (3.0 * a.planes[0].size());
}

TEST(ColourVideoTest, Ffv1IsLossless) {
  const Coded coded = EncodeAll(VideoCodec::kFfv1, 0);
  const auto decoded = Decode(VideoCodec::kFfv1, coded, 0, kFrames);
  ASSERT_EQ(decoded.size(), static_cast<std::size_t>(kFrames));
  for (int t = 0; t < kFrames; ++t) EXPECT_EQ(decoded.at(t).planes, MakePicture(t).planes);
}

TEST(ColourVideoTest, HevcAndAv1FollowTheQuantiserAndDecodeByGroup) {
  for (VideoCodec codec : {VideoCodec::kHevc, VideoCodec::kAv1}) {
    SCOPED_TRACE(std::string(VideoCodecName(codec)));
    const Coded fine = EncodeAll(codec, 8);
    const Coded coarse = EncodeAll(codec, codec == VideoCodec::kAv1 ? 50 : 40);
    const auto fine_decoded = Decode(codec, fine, 0, kFrames);
    const auto coarse_decoded = Decode(codec, coarse, 0, kFrames);
    ASSERT_EQ(fine_decoded.size(), static_cast<std::size_t>(kFrames));
    ASSERT_EQ(coarse_decoded.size(), static_cast<std::size_t>(kFrames));
    double fine_error = 0, coarse_error = 0;
    for (int t = 0; t < kFrames; ++t) {
      fine_error += MeanError(fine_decoded.at(t), MakePicture(t)) / kFrames;
      coarse_error += MeanError(coarse_decoded.at(t), MakePicture(t)) / kFrames;
    }
    EXPECT_LT(fine_error, 1.5);
    EXPECT_GT(coarse_error, fine_error);
    EXPECT_LT(coarse.bytes, fine.bytes);
    // The second group decodes on its own to the same pictures.
    const auto part = Decode(codec, fine, kGroup, 2 * kGroup);
    ASSERT_EQ(part.size(), static_cast<std::size_t>(kGroup));
    for (const auto& [pts, picture] : part) EXPECT_EQ(picture.planes, fine_decoded.at(pts).planes);
  }
}

TEST(ColourVideoTest, PicturesOfTheOtherFormatAreRefused) {
  auto colour = VideoEncoder::Create(ColourSettings(VideoCodec::kFfv1, 0));
  ASSERT_TRUE(colour.ok());
  std::vector<VideoPacket> packets;
  GreyPicture grey{kWidth, kHeight, 0,
                   std::vector<std::uint16_t>(static_cast<std::size_t>(kWidth) * kHeight)};
  EXPECT_EQ((*colour)->Encode(grey, true, &packets).code(), StatusCode::kInvalidArgument);
  ColourPicture ragged = MakePicture(0);
  ragged.planes[2].pop_back();
  EXPECT_EQ((*colour)->Encode(ragged, true, &packets).code(), StatusCode::kInvalidArgument);

  VideoEncoding grey_settings = ColourSettings(VideoCodec::kFfv1, 0);
  grey_settings.format = PictureFormat::kGrey10;
  auto grey_encoder = VideoEncoder::Create(grey_settings);
  ASSERT_TRUE(grey_encoder.ok());
  EXPECT_EQ((*grey_encoder)->Encode(MakePicture(0), true, &packets).code(),
            StatusCode::kInvalidArgument);

  // A grey stream read as colour is damaged data, not a crash.
  Coded coded;
  ASSERT_TRUE((*grey_encoder)->Encode(grey, true, &coded.packets).ok());
  ASSERT_TRUE((*grey_encoder)->Flush(&coded.packets).ok());
  auto decoder = VideoDecoder::Create(VideoCodec::kFfv1, kWidth, kHeight,
                                      (*grey_encoder)->extradata(), 1, PictureFormat::kColour8);
  ASSERT_TRUE(decoder.ok());
  std::vector<ColourPicture> pictures;
  Status status = (*decoder)->Decode(coded.packets[0], &pictures);
  if (status.ok()) status = (*decoder)->Flush(&pictures);
  EXPECT_EQ(status.code(), StatusCode::kCorrupt) << status.ToString();
  std::vector<GreyPicture> grey_pictures;
  EXPECT_EQ((*decoder)->Flush(&grey_pictures).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace meshvid
