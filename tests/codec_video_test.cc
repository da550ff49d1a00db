// Tests of the displacement video coder: lossless FFV1, lossy HEVC and AV1, closed groups.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>

#include "codec/dec/video_decoder.h"
#include "codec/enc/coding/video_encoder.h"

namespace meshvid {
namespace {

constexpr int kWidth = 64, kHeight = 48, kFrames = 24, kGroup = 8;

/// A smooth pattern moving over time, in 10-bit range.
GreyPicture MakePicture(int t) {
  GreyPicture p{kWidth, kHeight, t, {}};
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const double v = 512 + 300 * std::sin(0.15 * x + 0.1 * t) * std::cos(0.2 * y - 0.05 * t);
      p.samples.push_back(static_cast<std::uint16_t>(std::lround(v)));
    }
  }
  return p;
}

struct Coded {
  std::vector<std::uint8_t> extradata;
  std::vector<VideoPacket> packets;
  std::size_t bytes = 0;
};

Coded EncodeAll(VideoCodec codec, int qp) {
  VideoEncoding settings;
  settings.codec = codec;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.qp = qp;
  settings.threads = 1;
  auto encoder = VideoEncoder::Create(settings);
  EXPECT_TRUE(encoder.ok()) << encoder.status().ToString();
  Coded coded;
  if (!encoder.ok()) return coded;
  for (int t = 0; t < kFrames; ++t) {
    EXPECT_TRUE((*encoder)->Encode(MakePicture(t), t % kGroup == 0, &coded.packets).ok());
  }
  EXPECT_TRUE((*encoder)->Flush(&coded.packets).ok());
  coded.extradata = (*encoder)->extradata();
  for (const auto& p : coded.packets) coded.bytes += p.data.size();
  return coded;
}

/// Decodes the packets whose frames lie in [first, last) and returns pictures by pts.
std::map<std::int64_t, GreyPicture> Decode(VideoCodec codec, const Coded& coded, int first,
                                           int last) {
  auto decoder = VideoDecoder::Create(codec, kWidth, kHeight, coded.extradata);
  EXPECT_TRUE(decoder.ok()) << decoder.status().ToString();
  std::vector<GreyPicture> pictures;
  for (const auto& packet : coded.packets) {
    if (packet.pts < first || packet.pts >= last) continue;
    EXPECT_TRUE((*decoder)->Decode(packet, &pictures).ok());
  }
  EXPECT_TRUE((*decoder)->Flush(&pictures).ok());
  std::map<std::int64_t, GreyPicture> by_pts;
  for (auto& p : pictures) by_pts[p.pts] = std::move(p);
  return by_pts;
}

double MeanError(const GreyPicture& a, const GreyPicture& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    sum += std::abs(int(a.samples[i]) - int(b.samples[i]));
  }
  return sum / a.samples.size();
}

int MaxError(const GreyPicture& a, const GreyPicture& b) {
  int worst = 0;
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    worst = std::max(worst, std::abs(int(a.samples[i]) - int(b.samples[i])));
  }
  return worst;
}

TEST(VideoCoderTest, Ffv1IsLossless) {
  const Coded coded = EncodeAll(VideoCodec::kFfv1, 0);
  const auto decoded = Decode(VideoCodec::kFfv1, coded, 0, kFrames);
  ASSERT_EQ(decoded.size(), static_cast<std::size_t>(kFrames));
  for (int t = 0; t < kFrames; ++t) EXPECT_EQ(decoded.at(t).samples, MakePicture(t).samples);
}

TEST(VideoCoderTest, HevcErrorAndSizeFollowTheQuantiser) {
  const Coded fine = EncodeAll(VideoCodec::kHevc, 4);
  const Coded coarse = EncodeAll(VideoCodec::kHevc, 34);
  const auto fine_decoded = Decode(VideoCodec::kHevc, fine, 0, kFrames);
  const auto coarse_decoded = Decode(VideoCodec::kHevc, coarse, 0, kFrames);
  ASSERT_EQ(fine_decoded.size(), static_cast<std::size_t>(kFrames));
  ASSERT_EQ(coarse_decoded.size(), static_cast<std::size_t>(kFrames));
  int fine_error = 0, coarse_error = 0;
  double fine_mean = 0, coarse_mean = 0;
  for (int t = 0; t < kFrames; ++t) {
    fine_error = std::max(fine_error, MaxError(fine_decoded.at(t), MakePicture(t)));
    coarse_error = std::max(coarse_error, MaxError(coarse_decoded.at(t), MakePicture(t)));
    fine_mean += MeanError(fine_decoded.at(t), MakePicture(t)) / kFrames;
    coarse_mean += MeanError(coarse_decoded.at(t), MakePicture(t)) / kFrames;
  }
  // QP 4 is a 10-bit step of about one code; B frames are coded a few QP coarser.
  EXPECT_LE(fine_error, 8);
  EXPECT_LT(fine_mean, 1.5);
  EXPECT_GT(coarse_error, fine_error);
  EXPECT_GT(coarse_mean, 2 * fine_mean);
  EXPECT_LT(coarse.bytes, fine.bytes);
  // Raw size is 64 * 48 * 24 * 10 bits = 92 kB; a smooth pattern codes far smaller.
  EXPECT_LT(fine.bytes, 40000u);
}

TEST(VideoCoderTest, EveryGroupDecodesOnItsOwn) {
  for (VideoCodec codec : {VideoCodec::kHevc, VideoCodec::kAv1}) {
    const Coded coded = EncodeAll(codec, 20);
    const auto all = Decode(codec, coded, 0, kFrames);
    ASSERT_EQ(all.size(), static_cast<std::size_t>(kFrames)) << VideoCodecName(codec);
    for (int group = 0; group < kFrames / kGroup; ++group) {
      const auto part = Decode(codec, coded, group * kGroup, (group + 1) * kGroup);
      ASSERT_EQ(part.size(), static_cast<std::size_t>(kGroup)) << VideoCodecName(codec);
      for (const auto& [pts, picture] : part) EXPECT_EQ(picture.samples, all.at(pts).samples);
    }
  }
}

TEST(VideoCoderTest, RejectsBadSettingsAndGarbage) {
  VideoEncoding settings;
  settings.width = 60;  // not a multiple of 8
  settings.height = 48;
  EXPECT_EQ(VideoEncoder::Create(settings).status().code(), StatusCode::kInvalidArgument);
  settings.width = 64;
  settings.qp = 99;
  EXPECT_EQ(VideoEncoder::Create(settings).status().code(), StatusCode::kInvalidArgument);

  const Coded coded = EncodeAll(VideoCodec::kHevc, 20);
  auto decoder = VideoDecoder::Create(VideoCodec::kHevc, kWidth, kHeight, coded.extradata);
  ASSERT_TRUE(decoder.ok());
  VideoPacket garbage;
  garbage.data.assign(200, 0xA5);
  std::vector<GreyPicture> pictures;
  const Status status = (*decoder)->Decode(garbage, &pictures);
  // Garbage either fails to decode or yields nothing; it never yields a wrong-size picture.
  if (!status.ok()) {
    EXPECT_EQ(status.code(), StatusCode::kCorrupt);
  }
  for (const auto& p : pictures) EXPECT_EQ(p.samples.size(), std::size_t{kWidth * kHeight});
  EXPECT_EQ(VideoDecoder::Create(VideoCodec::kHevc, 0, 10, {}).status().code(),
            StatusCode::kCorrupt);
}

}  // namespace
}  // namespace meshvid
