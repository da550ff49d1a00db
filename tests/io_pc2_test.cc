// Pc2Reader / Pc2Writer: round trip, header validation, truncation, NaN frames, shared data.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_util.h"
#include "tools/io/mesh_io.h"
#include "tools/io/pc2.h"

namespace meshvid {
namespace {

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << (text) << "\n  lacks: " << (part)

std::vector<Eigen::Vector3f> MakeFrame(int points, float t) {
  std::vector<Eigen::Vector3f> frame;
  for (int i = 0; i < points; ++i) {
    frame.emplace_back(0.1f * i + t, -1.0f / (i + 1), t * t + 1e-7f * i);
  }
  return frame;
}

// Writes a 3-frame, 5-point file at `path`.
void WriteSample(const std::string& path) {
  auto writer = Pc2Writer::Create(path, 5, 10.0f, 0.5f);
  ASSERT_TRUE(writer.ok()) << writer.status().ToString();
  for (int f = 0; f < 3; ++f) ASSERT_TRUE((*writer)->AppendFrame(MakeFrame(5, f * 0.25f)).ok());
  ASSERT_TRUE((*writer)->Finish().ok());
}

void ExpectOpenError(const std::string& path, StatusCode code, const std::string& problem) {
  const auto reader = Pc2Reader::Open(path);
  ASSERT_FALSE(reader.ok());
  EXPECT_EQ(reader.status().code(), code) << reader.status().ToString();
  EXPECT_EQ(reader.status().message().rfind(path + ": ", 0), 0u) << reader.status().message();
  EXPECT_CONTAINS(reader.status().message(), problem);
}

// Overwrites 4 bytes at `offset` of the file with `value`.
template <typename T>
void Patch(const std::string& path, std::size_t offset, T value) {
  std::string data = testing::ReadFile(path);
  std::memcpy(data.data() + offset, &value, 4);
  testing::WriteFile(path, data);
}

TEST(Pc2Test, RoundTrip) {
  testing::TempDir dir;
  const std::string path = dir.File("a.pc2");
  WriteSample(path);
  EXPECT_EQ(testing::ReadFile(path).size(), 32u + 3 * 5 * 12);
  auto reader = Pc2Reader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  const Pc2Header& h = (*reader)->header();
  EXPECT_EQ(h.version, 1);
  EXPECT_EQ(h.num_points, 5);
  EXPECT_EQ(h.num_samples, 3);
  EXPECT_EQ(h.start_frame, 10.0f);
  EXPECT_EQ(h.sample_rate, 0.5f);
  for (int f : {2, 0, 1}) {  // any order: the reader seeks
    const auto frame = (*reader)->ReadFrame(f);
    ASSERT_TRUE(frame.ok()) << frame.status().ToString();
    EXPECT_EQ(*frame, MakeFrame(5, f * 0.25f)) << "frame " << f;
  }
  for (int f : {-1, 3}) {
    const auto frame = (*reader)->ReadFrame(f);
    ASSERT_FALSE(frame.ok());
    EXPECT_EQ(frame.status().code(), StatusCode::kInvalidArgument);
    EXPECT_CONTAINS(frame.status().message(), "out of range (the file has 3 samples)");
  }
}

TEST(Pc2Test, EmptyCacheAndWriterMisuse) {
  testing::TempDir dir;
  const std::string path = dir.File("empty.pc2");
  auto writer = Pc2Writer::Create(path, 2);
  ASSERT_TRUE(writer.ok());
  const Status wrong = (*writer)->AppendFrame(MakeFrame(3, 0));
  EXPECT_EQ(wrong.code(), StatusCode::kInvalidArgument);
  EXPECT_CONTAINS(wrong.message(), "frame has 3 points, the PC2 file has 2");
  ASSERT_TRUE((*writer)->Finish().ok());
  EXPECT_EQ((*writer)->AppendFrame(MakeFrame(2, 0)).code(), StatusCode::kInvalidArgument);
  const auto reader = Pc2Reader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_EQ((*reader)->header().num_samples, 0);
  EXPECT_EQ(Pc2Writer::Create(dir.File("x.pc2"), 0).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(Pc2Writer::Create(dir.File("empty.pc2/y.pc2"), 4).status().code(), StatusCode::kIoError);
}

TEST(Pc2Test, CorruptHeaders) {
  testing::TempDir dir;
  const std::string path = dir.File("c.pc2");
  ExpectOpenError(path, StatusCode::kNotFound, "no such file");
  testing::WriteFile(path, "POINTCACHE2");
  ExpectOpenError(path, StatusCode::kCorrupt, "shorter than the 32-byte header");
  WriteSample(path);
  Patch(path, 0, std::int32_t{0x4e494f50 + 1});  // "QOIN..."
  ExpectOpenError(path, StatusCode::kCorrupt, "missing the POINTCACHE2 signature");
  WriteSample(path);
  Patch(path, 12, std::int32_t{2});
  ExpectOpenError(path, StatusCode::kCorrupt, "unsupported PC2 version 2");
  WriteSample(path);
  Patch(path, 16, std::int32_t{0});
  ExpectOpenError(path, StatusCode::kCorrupt, "numPoints = 0 (must be at least 1)");
  WriteSample(path);
  Patch(path, 28, std::int32_t{-1});
  ExpectOpenError(path, StatusCode::kCorrupt, "numSamples = -1 (must not be negative)");
  WriteSample(path);
  Patch(path, 28, std::int32_t{2000000000});  // absurd: must fail on length, not allocate
  ExpectOpenError(path, StatusCode::kCorrupt, "truncated PC2 file");
}

TEST(Pc2Test, TruncatedFile) {
  testing::TempDir dir;
  const std::string path = dir.File("t.pc2");
  WriteSample(path);
  std::string data = testing::ReadFile(path);
  data.resize(data.size() - 4);
  testing::WriteFile(path, data);
  ExpectOpenError(path, StatusCode::kCorrupt,
                  "truncated PC2 file: 3 samples of 5 points need 212 bytes, the file has 208");
}

TEST(Pc2Test, NonFiniteValueNamesFrameAndPoint) {
  testing::TempDir dir;
  const std::string path = dir.File("n.pc2");
  WriteSample(path);
  Patch(path, 32 + (1 * 5 + 2) * 12 + 4, std::numeric_limits<float>::quiet_NaN());
  auto reader = Pc2Reader::Open(path);
  ASSERT_TRUE(reader.ok());
  EXPECT_TRUE((*reader)->ReadFrame(0).ok());
  const auto frame = (*reader)->ReadFrame(1);
  ASSERT_FALSE(frame.ok());
  EXPECT_EQ(frame.status().code(), StatusCode::kCorrupt);
  EXPECT_EQ(frame.status().message(),
            path + ": frame 1 point 2 has a NaN or infinite coordinate");
  EXPECT_TRUE((*reader)->ReadFrame(2).ok());  // the reader recovers after an error
}

TEST(Pc2SharedDataTest, SambaMatchesItsTemplate) {
  MESHVID_REQUIRE_SHARED_DATA();
  auto reader = Pc2Reader::Open(shared_data + "/sequences/samba.pc2");
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_EQ((*reader)->header().num_points, 9971);
  EXPECT_EQ((*reader)->header().num_samples, 175);
  const auto first = (*reader)->ReadFrame(0);
  ASSERT_TRUE(first.ok()) << first.status().ToString();
  const auto mesh = ReadMesh(shared_data + "/sequences/samba.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  ASSERT_EQ(first->size(), mesh->vertex_count());
  float worst = 0;
  for (std::size_t i = 0; i < first->size(); ++i) {
    worst = std::max(worst, ((*first)[i] - mesh->positions[i]).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-6f);  // the OBJ holds frame 0 with 6 decimals
  const auto last = (*reader)->ReadFrame(174);
  ASSERT_TRUE(last.ok()) << last.status().ToString();
  EXPECT_NE((*last)[0], (*first)[0]);
}

}  // namespace
}  // namespace meshvid
