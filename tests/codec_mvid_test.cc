// Round trips of analytic representations through MvidWriter and MvidDecoder: a sphere-like
// base mesh in two blended segments, known transforms and a known displacement function.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>

#include "codec/dec/mvid_decoder.h"
#include "codec/enc/coding/mvid_writer.h"
#include "format/container_reader.h"
#include "format/container_writer.h"
#include "tests/analytic_mvid.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

struct Representation {
  TriangleMesh base = testing::SphereMesh(2);
  MotionModel motion = testing::TwoSegments(testing::SphereMesh(2));
  int frames = 12;
};

/// Writes the analytic representation with `settings` and returns the file's bytes.
std::vector<std::uint8_t> WriteRepresentation(const Representation& rep,
                                              const MvidWriterSettings& settings,
                                              MvidWriteStats* stats = nullptr) {
  auto bytes = testing::WriteAnalyticMvid(rep.base, rep.motion, rep.frames, settings, stats);
  EXPECT_TRUE(bytes.ok()) << bytes.status().ToString();
  return bytes.ok() ? *bytes : std::vector<std::uint8_t>{};
}

/// Largest distance between decoded and expected positions over all frames at `level`;
/// `rms` (if given) receives the root mean square distance.
float MaxError(MvidDecoder& decoder, int level, int frames, float* rms = nullptr) {
  const auto error = testing::MeasureReconstructionError(decoder, level, frames);
  EXPECT_TRUE(error.ok()) << error.status().ToString();
  if (!error.ok()) return std::numeric_limits<float>::infinity();
  if (rms != nullptr) *rms = error->rms;
  return error->max;
}

// The detail spans [-0.02, 0.02]: a 10-bit step of 0.04 / 1023.
constexpr float kStep = 0.04f / 1023;

class MvidPackingTest : public ::testing::TestWithParam<DisplacementPacking> {};

TEST_P(MvidPackingTest, Ffv1IsExactUpToQuantisationAtEveryLevel) {
  Representation rep;
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.packing = GetParam();
  settings.levels = 3;
  settings.gof_size = 5;
  const std::vector<std::uint8_t> bytes = WriteRepresentation(rep, settings);
  auto decoder = MvidDecoder::OpenMemory(bytes);
  ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
  const MvidInfo& info = (*decoder)->info();
  EXPECT_EQ(info.frame_count, 12u);
  EXPECT_EQ(info.gof_count, 3u);
  EXPECT_EQ(info.levels, 3);
  EXPECT_EQ(info.base_vertices, rep.base.vertex_count());
  EXPECT_EQ(info.segments, 2u);
  EXPECT_TRUE(info.indexed);
  for (int level = 0; level <= 3; ++level) {
    EXPECT_LE(MaxError(**decoder, level, rep.frames), kStep / 2 * 1.01f + 1e-6f) << level;
    // Fixed connectivity: the same triangles at every frame, a closed surface.
    auto first = (*decoder)->DecodeFrame(0, level);
    auto last = (*decoder)->DecodeFrame(11, level);
    ASSERT_TRUE(first.ok() && last.ok());
    EXPECT_EQ(first->triangles, last->triangles);
    EXPECT_EQ(first->triangle_count(), rep.base.triangle_count() << (2 * level));
    EXPECT_TRUE(ValidateMesh(*last, "decoded").ok());
  }
  // Random access: a later frame first, then an earlier group.
  std::vector<Eigen::Vector3f> late, early;
  EXPECT_TRUE((*decoder)->DecodePositions(11, 2, &late).ok());
  EXPECT_TRUE((*decoder)->DecodePositions(1, 2, &early).ok());
  EXPECT_EQ((*decoder)->DecodePositions(12, 2, &late).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ((*decoder)->DecodePositions(0, 4, &late).code(), StatusCode::kInvalidArgument);
}

INSTANTIATE_TEST_SUITE_P(BothPackings, MvidPackingTest,
                         ::testing::Values(DisplacementPacking::kLatticeOrder,
                                           DisplacementPacking::kTriangleBlocks));

// Measured on this content (12 frames of 4,098 samples) by bench/packing_bench: HEVC QP 8 codes
// 32.5 kB at 2.86 steps RMS in lattice order and 50.9 kB at 2.42 in triangle blocks; QP 32
// 11.3 kB at 33.1 steps; AV1 CRF 8 (blocks) 29.6 kB at 4.15. The bounds below allow +-30% on
// size and 1.5x on error around those figures.
TEST(MvidRoundTripTest, LossyCodecsStayWithinErrorAndSizeBounds) {
  Representation rep;
  struct Point {
    VideoCodec codec;
    DisplacementPacking packing;
    int qp;
    std::uint64_t bytes;  // measured video bytes
    float rms_steps;      // measured RMS error in quantisation steps
  };
  constexpr auto kLattice = DisplacementPacking::kLatticeOrder;
  constexpr auto kBlocks = DisplacementPacking::kTriangleBlocks;
  for (const Point& point : {Point{VideoCodec::kHevc, kLattice, 8, 32548, 2.86f},
                             Point{VideoCodec::kHevc, kLattice, 32, 11320, 33.1f},
                             Point{VideoCodec::kHevc, kBlocks, 8, 50907, 2.42f},
                             Point{VideoCodec::kAv1, kBlocks, 8, 29564, 4.15f}}) {
    MvidWriterSettings settings;
    settings.codec = point.codec;
    settings.packing = point.packing;
    settings.levels = 3;
    settings.gof_size = 6;
    settings.qp = point.qp;
    MvidWriteStats stats;
    const std::vector<std::uint8_t> bytes = WriteRepresentation(rep, settings, &stats);
    auto decoder = MvidDecoder::OpenMemory(bytes);
    ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
    float rms = 0;
    MaxError(**decoder, 3, rep.frames, &rms);
    const std::string what = std::string(VideoCodecName(point.codec)) + " qp " +
                             std::to_string(point.qp) + " packing " +
                             std::to_string(static_cast<int>(point.packing));
    EXPECT_LE(rms, 1.5f * point.rms_steps * kStep) << what;
    EXPECT_GE(stats.video_bytes, 0.7 * point.bytes) << what;
    EXPECT_LE(stats.video_bytes, 1.3 * point.bytes) << what;
    EXPECT_EQ(stats.total_bytes, bytes.size()) << what;
  }
}

TEST(MvidRoundTripTest, TruncatedFilesKeepTheirCompleteGroups) {
  Representation rep;
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.levels = 2;
  settings.gof_size = 4;
  const std::vector<std::uint8_t> bytes = WriteRepresentation(rep, settings);
  auto whole = MvidDecoder::OpenMemory(bytes);
  ASSERT_TRUE(whole.ok());
  // Without the trailer the groups are found by scanning; all three are complete.
  auto untrailed = MvidDecoder::OpenMemory({bytes.begin(), bytes.end() - 40});
  ASSERT_TRUE(untrailed.ok()) << untrailed.status().ToString();
  EXPECT_FALSE((*untrailed)->info().indexed);
  EXPECT_EQ((*untrailed)->info().frame_count, 12u);
  // Cut inside the last group: the first two groups (8 frames) stay decodable.
  auto container = ContainerReader::OpenMemory(bytes);
  ASSERT_TRUE(container.ok());
  ASSERT_EQ(container->gof_count(), 3u);
  const std::size_t last_group = container->gofs()[2].offset;
  for (std::size_t cut : {last_group + 5, last_group + 200}) {
    auto decoder = MvidDecoder::OpenMemory({bytes.begin(), bytes.begin() + cut});
    ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
    EXPECT_FALSE((*decoder)->info().indexed);
    ASSERT_EQ((*decoder)->info().frame_count, 8u);
    for (std::uint32_t f = 0; f < 8; ++f) {
      auto a = (*decoder)->DecodeFrame(f, 2);
      auto b = (*whole)->DecodeFrame(f, 2);
      ASSERT_TRUE(a.ok()) << a.status().ToString();
      EXPECT_EQ(a->positions, b->positions);
    }
    EXPECT_EQ((*decoder)->DecodeFrame(8, 2).status().code(), StatusCode::kInvalidArgument);
  }
  // Cut before the first group: opening fails or yields no frames, never crashes.
  for (std::size_t cut = 0; cut < 200; cut += 13) {
    auto decoder = MvidDecoder::OpenMemory({bytes.begin(), bytes.begin() + cut});
    if (decoder.ok()) {
      EXPECT_EQ((*decoder)->info().frame_count, 0u);
    }
  }
}

TEST(MvidRoundTripTest, StreamsDecodeFrontToBack) {
  Representation rep;
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kHevc;
  settings.levels = 2;
  settings.gof_size = 5;
  settings.frame_count = 12;
  const std::vector<std::uint8_t> bytes = WriteRepresentation(rep, settings);
  auto whole = MvidDecoder::OpenMemory(bytes);
  ASSERT_TRUE(whole.ok());
  std::istringstream in(std::string(bytes.begin(), bytes.end()));
  auto stream = MvidDecoder::OpenStream(in);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  EXPECT_EQ((*stream)->info().frame_count, 12u);
  for (std::uint32_t f : {0u, 1u, 4u, 4u, 7u, 11u}) {
    auto a = (*stream)->DecodeFrame(f, 2);
    auto b = (*whole)->DecodeFrame(f, 2);
    ASSERT_TRUE(a.ok()) << a.status().ToString();
    EXPECT_EQ(a->positions, b->positions) << f;
  }
  EXPECT_EQ((*stream)->DecodeFrame(3, 2).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ((*stream)->MeasureStreams().status().code(), StatusCode::kUnsupported);
  // A stream cut inside the third group still gives the first two.
  std::istringstream cut(std::string(bytes.begin(), bytes.begin() + bytes.size() * 5 / 6));
  auto partial = MvidDecoder::OpenStream(cut);
  ASSERT_TRUE(partial.ok());
  EXPECT_TRUE((*partial)->DecodeFrame(9, 1).ok());
  EXPECT_FALSE((*partial)->DecodeFrame(11, 1).ok());
}

TEST(MvidRoundTripTest, WriterRejectsInconsistentInput) {
  Representation rep;
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.levels = 1;
  auto writer = MvidWriter::Create([](std::span<const std::uint8_t>) { return Status::Ok(); },
                                   rep.base, rep.motion, settings);
  ASSERT_TRUE(writer.ok());
  const std::size_t samples = (*writer)->subdivision().samples().size();
  EXPECT_EQ((*writer)->WriteGroup({testing::TransformsAt(0)}, {std::vector<float>(samples - 1)}).code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ((*writer)->WriteGroup({{RigidTransform{}}}, {std::vector<float>(samples)}).code(),
            StatusCode::kInvalidArgument);
  std::vector<float> field(samples, 0.0f);
  field[3] = std::nanf("");
  EXPECT_EQ((*writer)->WriteGroup({testing::TransformsAt(0)}, {field}).code(),
            StatusCode::kInvalidArgument);
  MotionModel wrong = rep.motion;
  wrong.blends.pop_back();
  EXPECT_FALSE(MvidWriter::Create([](std::span<const std::uint8_t>) { return Status::Ok(); },
                                  rep.base, wrong, settings)
                   .ok());
  // A base mesh coder free to renumber vertices would break the blends' order: refused.
  MvidWriterSettings reordering = settings;
  reordering.base.allow_reorder = true;
  auto refused = MvidWriter::Create([](std::span<const std::uint8_t>) { return Status::Ok(); },
                                    rep.base, rep.motion, reordering);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(refused.status().message().find("allow_reorder"), std::string::npos);
}

TEST(MvidRoundTripTest, AKeyGroupRoundsItsTransformsAboutPivotsWhenThatCodesFewerBytes) {
  // Deformation nodes 0.5 apart on a unit sphere 20 units from the origin: rounded about the
  // origin, a rotation step must hold points 22 away; about its node, 1 or so (with a quarter
  // of the bound).
  Representation rep;
  for (Eigen::Vector3f& p : rep.base.positions) p += Eigen::Vector3f(20, 0, 0);
  rep.motion = testing::DeformationNodes(rep.base, 0.5f);
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.levels = 1;
  settings.motion.translation_step = 1e-4f;
  settings.motion.rotation_step = 1e-4f / 22;
  const std::uint32_t segments = rep.motion.segment_count;
  // A tracked node jitters by a few degrees and millimetres from frame to frame.
  std::mt19937 random(3);
  std::normal_distribution<float> jitter(0.0f, 0.02f);
  std::vector<std::vector<RigidTransform>> jittery(8), translated(8);
  for (int f = 0; f < 8; ++f) {
    for (std::uint32_t s = 0; s < segments; ++s) {
      RigidTransform t;
      t.rotation = Eigen::AngleAxisf(jitter(random), Eigen::Vector3f(1, 2, 3).normalized());
      t.translation = Eigen::Vector3f(jitter(random), jitter(random), 0.01f * f);
      jittery[f].push_back(t);
      translated[f].push_back(RigidTransform{Eigen::Quaternionf::Identity(), t.translation});
    }
  }
  const auto sink = [](std::span<const std::uint8_t>) { return Status::Ok(); };
  auto writer = MvidWriter::Create(sink, rep.base, rep.motion, settings, jittery);
  ASSERT_TRUE(writer.ok()) << writer.status().ToString();
  EXPECT_GT((*writer)->motion_quantization().rotation_step, 2 * settings.motion.rotation_step);
  EXPECT_EQ((*writer)->motion_quantization().translation_step, settings.motion.translation_step);
  // Every base vertex lands within the stated bound of where the track puts it.
  const auto decoded = (*writer)->DequantizeTransforms(jittery);
  std::vector<Eigen::Vector3f> expected, posed;
  for (int f = 0; f < 8; ++f) {
    PoseVertices((*writer)->motion(), jittery[f], (*writer)->decoded_base().positions, &expected);
    PoseVertices((*writer)->motion(), decoded[f], (*writer)->decoded_base().positions, &posed);
    for (std::size_t v = 0; v < posed.size(); ++v) {
      EXPECT_LE((posed[v] - expected[v]).norm(), std::sqrt(3.0f) * 1e-4f * 1.01f) << f << " " << v;
    }
  }
  // Without rotations the pivots gain nothing: the steps stay the settings'.
  auto plain = MvidWriter::Create(sink, rep.base, rep.motion, settings, translated);
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ((*plain)->motion_quantization().rotation_step, settings.motion.rotation_step);
  // And so without a track.
  auto untracked = MvidWriter::Create(sink, rep.base, rep.motion, settings);
  ASSERT_TRUE(untracked.ok());
  EXPECT_EQ((*untracked)->motion_quantization().rotation_step, settings.motion.rotation_step);
}

/// Every readable frame of `bytes` at every level; returns the first error.
Status DecodeEverything(std::vector<std::uint8_t> bytes) {
  MESHVID_ASSIGN_OR_RETURN(auto decoder, MvidDecoder::OpenMemory(std::move(bytes)));
  for (std::uint32_t f = 0; f < decoder->info().frame_count; ++f) {
    for (int level = 0; level <= decoder->info().levels; ++level) {
      MESHVID_ASSIGN_OR_RETURN(const TriangleMesh mesh, decoder->DecodeFrame(f, level));
      MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, "decoded"));
    }
  }
  return Status::Ok();
}

TEST(MvidBadInputTest, FlippedBitsAreErrorsNeverCrashes) {
  const std::string golden = testing::ReadFile(std::string(MESHVID_GOLDEN_DIR) + "/sphere.v1.mvid");
  const std::vector<std::uint8_t> bytes(golden.begin(), golden.end());
  ASSERT_TRUE(DecodeEverything(bytes).ok());
  int failures = 0, flips = 0;
  for (std::size_t bit = 0; bit < bytes.size() * 8; bit += 61) {
    std::vector<std::uint8_t> flipped = bytes;
    flipped[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    ++flips;
    // CRCs catch a flip in any chunk; a flip in the index or trailer makes the reader fall
    // back to scanning, which still decodes everything correctly.
    if (!DecodeEverything(std::move(flipped)).ok()) ++failures;
  }
  EXPECT_GT(failures, flips * 9 / 10);
}

TEST(MvidBadInputTest, AVideoStreamThatDoesNotDecodeIsAnError) {
  auto reader = ContainerReader::OpenFile(std::string(MESHVID_GOLDEN_DIR) + "/sphere.v1.mvid");
  ASSERT_TRUE(reader.ok());
  // Re-wrap the file with garbage video packets in its second group (CRCs stay valid).
  std::vector<std::uint8_t> out;
  ContainerWriter writer([&out](std::span<const std::uint8_t> b) {
    out.insert(out.end(), b.begin(), b.end());
    return Status::Ok();
  });
  ASSERT_TRUE(writer.Begin(reader->header()).ok());
  ASSERT_TRUE(writer.WriteBase(*reader->ReadBase()).ok());
  ASSERT_TRUE(writer.WriteMotion(*reader->ReadMotion()).ok());
  for (std::size_t k = 0; k < reader->gof_count(); ++k) {
    GroupOfFrames gof = *reader->ReadGof(k);
    if (k == 1) {
      for (auto& packet : gof.packets[0]) packet.assign(packet.size(), 0x5A);
    }
    ASSERT_TRUE(writer.WriteGof(gof).ok());
  }
  ASSERT_TRUE(writer.Finish().ok());
  auto decoder = MvidDecoder::OpenMemory(out);
  ASSERT_TRUE(decoder.ok());
  EXPECT_TRUE((*decoder)->DecodeFrame(0, 2).ok());  // the first group is intact
  const auto broken = (*decoder)->DecodeFrame(5, 2);
  EXPECT_EQ(broken.status().code(), StatusCode::kCorrupt) << broken.status().ToString();
}

// tests/golden/sphere.v1.mvid: written by this test (with MESHVID_WRITE_GOLDEN) before the
// writer moved to format_version 2; decoded by it always. Never delete or rewrite a golden file
// when the format moves on.
TEST(MvidGoldenTest, Version1FileStillDecodes) {
  Representation rep;
  rep.base = testing::SphereMesh(1);
  rep.motion = testing::TwoSegments(rep.base);
  rep.frames = 6;
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.levels = 2;
  settings.gof_size = 4;
  settings.metadata_json = R"({"golden":"sphere","format_version":1})";
  auto decoder = MvidDecoder::OpenFile(std::string(MESHVID_GOLDEN_DIR) + "/sphere.v1.mvid");
  ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
  EXPECT_EQ((*decoder)->info().format_version, 1u);
  EXPECT_EQ((*decoder)->info().key_groups.size(), 1u);
  EXPECT_EQ((*decoder)->info().frame_count, 6u);
  EXPECT_EQ((*decoder)->info().base_vertices, 18u);
  EXPECT_EQ((*decoder)->info().metadata_json, settings.metadata_json);
  EXPECT_LE(MaxError(**decoder, 2, rep.frames), kStep / 2 * 1.01f + 1e-6f);
}

// Three key groups of different bases (18, 66 and 18 vertices): frames 0-4, 5-8, 9-11.
std::vector<testing::AnalyticKeyGroup> ThreeKeyGroups() {
  return {{testing::SphereMesh(1), 0}, {testing::SphereMesh(2), 5}, {testing::LatLongSphere(4, 4), 9}};
}

TEST(MvidKeyGroupTest, EveryKeyGroupDecodesWithItsOwnConnectivity) {
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.levels = 2;
  settings.gof_size = 3;
  MvidWriteStats stats;
  auto bytes = testing::WriteAnalyticKeyGroups(ThreeKeyGroups(), 12, settings, &stats);
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  auto decoder = MvidDecoder::OpenMemory(*bytes);
  ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
  const MvidInfo& info = (*decoder)->info();
  EXPECT_EQ(info.format_version, 2u);
  ASSERT_EQ(info.key_groups.size(), 3u);
  // Groups of frames split at key-group boundaries: 3+2 | 3+1 | 3.
  EXPECT_EQ(info.gof_count, 5u);
  EXPECT_EQ(info.key_groups[1].first_frame, 5u);
  EXPECT_EQ(info.key_groups[1].frame_count, 4u);
  EXPECT_EQ(info.key_groups[2].first_gof, 4u);
  EXPECT_EQ(*(*decoder)->KeyGroupOf(4), 0u);
  EXPECT_EQ(*(*decoder)->KeyGroupOf(5), 1u);
  EXPECT_EQ(*(*decoder)->KeyGroupOf(11), 2u);

  // Exact up to quantisation in every key group, read in order and out of order.
  EXPECT_LE(MaxError(**decoder, 2, 12), kStep / 2 * 1.01f + 1e-6f);
  const std::vector<std::size_t> vertices = {18, 66, 18};
  for (std::uint32_t f : {11u, 0u, 7u, 3u, 9u, 5u}) {
    const std::uint32_t k = *(*decoder)->KeyGroupOf(f);
    auto mesh = (*decoder)->DecodeFrame(f, 0);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    EXPECT_EQ(mesh->vertex_count(), vertices[k]) << f;
    EXPECT_EQ((*decoder)->current_key_group(), k);
    auto triangles = (*decoder)->TrianglesOf(f, 1);
    ASSERT_TRUE(triangles.ok());
    EXPECT_EQ(triangles.value()->size(), (*decoder)->base_mesh().triangle_count() * 4);
  }
  // The same triangles within a key group, different ones across.
  const auto a = (*decoder)->DecodeFrame(5, 1);
  const auto b = (*decoder)->DecodeFrame(8, 1);
  const auto c = (*decoder)->DecodeFrame(9, 1);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  EXPECT_EQ(a->triangles, b->triangles);
  EXPECT_NE(a->triangles, c->triangles);

  auto described = (*decoder)->DescribeKeyGroup(1);
  ASSERT_TRUE(described.ok()) << described.status().ToString();
  EXPECT_EQ(described->base_vertices, 66u);
  EXPECT_EQ(described->span.first_frame, 5u);
  EXPECT_EQ(described->vertices_per_level.back(), (*decoder)->DecodeFrame(6, 2)->vertex_count());
  auto sizes = (*decoder)->MeasureStreams();
  ASSERT_TRUE(sizes.ok());
  ASSERT_EQ(sizes->key_group_bytes.size(), 3u);
  EXPECT_EQ(sizes->base_bytes, stats.base_bytes);
  EXPECT_EQ(sizes->motion_bytes, stats.motion_bytes);

  // A stream decodes across key groups front to back.
  std::istringstream in(std::string(bytes->begin(), bytes->end()));
  auto stream = MvidDecoder::OpenStream(in);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  for (std::uint32_t f = 0; f < 12; ++f) {
    auto streamed = (*stream)->DecodeFrame(f, 1);
    auto indexed = (*decoder)->DecodeFrame(f, 1);
    ASSERT_TRUE(streamed.ok()) << f << ": " << streamed.status().ToString();
    EXPECT_EQ(streamed->positions, indexed->positions) << f;
    EXPECT_EQ(streamed->triangles, indexed->triangles) << f;
  }
  EXPECT_EQ((*stream)->info().key_groups.size(), 3u);

  // Cut inside the last key group's BASE: the first two key groups still decode.
  auto reader = ContainerReader::OpenMemory(*bytes);
  ASSERT_TRUE(reader.ok());
  const std::uint64_t cut_at = reader->key_groups()[2].base_offset + 20;
  auto cut = MvidDecoder::OpenMemory(std::vector<std::uint8_t>(bytes->begin(),
                                                               bytes->begin() + cut_at));
  ASSERT_TRUE(cut.ok()) << cut.status().ToString();
  EXPECT_EQ((*cut)->info().frame_count, 9u);
  EXPECT_EQ((*cut)->info().key_groups.size(), 2u);
  EXPECT_TRUE((*cut)->DecodeFrame(8, 2).ok());
}

// tests/golden/sphere.v2.mvid: three key groups, written by this test when
// MESHVID_WRITE_GOLDEN names a folder, decoded by it always.
TEST(MvidGoldenTest, Version2FileWithKeyGroupsStillDecodes) {
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.levels = 2;
  settings.gof_size = 3;
  settings.metadata_json = R"({"golden":"sphere key groups","format_version":2})";
  if (const char* out = std::getenv("MESHVID_WRITE_GOLDEN")) {
    auto bytes = testing::WriteAnalyticKeyGroups(ThreeKeyGroups(), 12, settings);
    ASSERT_TRUE(bytes.ok());
    std::ofstream(std::string(out) + "/sphere.v2.mvid", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes->data()), bytes->size());
  }
  auto decoder = MvidDecoder::OpenFile(std::string(MESHVID_GOLDEN_DIR) + "/sphere.v2.mvid");
  ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
  EXPECT_EQ((*decoder)->info().format_version, 2u);
  EXPECT_EQ((*decoder)->info().frame_count, 12u);
  EXPECT_EQ((*decoder)->info().key_groups.size(), 3u);
  EXPECT_EQ((*decoder)->info().metadata_json, settings.metadata_json);
  EXPECT_LE(MaxError(**decoder, 2, 12), kStep / 2 * 1.01f + 1e-6f);
}

// tests/golden/sphere.nodes.mvid: MOTN version 3 (spec/mvid-codec.md 2.3), a deformation
// graph whose blends the decoder derives from the base mesh; written by this test when
// MESHVID_WRITE_GOLDEN names a folder, decoded by it always.
TEST(MvidGoldenTest, DeformationNodesFileDecodes) {
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.levels = 2;
  settings.gof_size = 3;
  settings.metadata_json = R"({"golden":"sphere deformation nodes"})";
  const TriangleMesh base = testing::SphereMesh(2);
  const MotionModel nodes = testing::DeformationNodes(base, 0.6f);
  ASSERT_GT(nodes.segment_count, 8u);
  MvidWriteStats stats;
  auto bytes = testing::WriteAnalyticMvid(base, nodes, 6, settings, &stats);
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  // A u32 per node instead of 25 bytes per vertex (258 vertices: 6,450 bytes raw).
  EXPECT_LT(stats.motion_bytes, 40 + 4 * nodes.segment_count);
  if (const char* out = std::getenv("MESHVID_WRITE_GOLDEN")) {
    std::ofstream(std::string(out) + "/sphere.nodes.mvid", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes->data()), bytes->size());
  }
  for (const bool golden : {false, true}) {
    auto decoder = golden ? MvidDecoder::OpenFile(std::string(MESHVID_GOLDEN_DIR) +
                                                  "/sphere.nodes.mvid")
                          : MvidDecoder::OpenMemory(*bytes);
    ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
    EXPECT_EQ((*decoder)->info().segments, nodes.segment_count);
    ASSERT_TRUE((*decoder)->DecodeFrame(0, 0).ok());
    EXPECT_EQ((*decoder)->motion().node_vertices.size(), nodes.segment_count);
    EXPECT_LE(MaxError(**decoder, 2, 6), kStep / 2 * 1.01f + 1e-6f) << "golden " << golden;
  }
}

// tests/golden/sphere.planes.mvid: GOF side information version 2 (spec/mvid-codec.md 2.4),
// the transforms' deltas in byte planes; written by this test when MESHVID_WRITE_GOLDEN names
// a folder, decoded by it always. The golden files above hold side information version 1.
TEST(MvidGoldenTest, TransformBytePlanesFileDecodes) {
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.levels = 2;
  settings.gof_size = 3;
  settings.metadata_json = R"({"golden":"sphere transform byte planes"})";
  auto bytes = testing::WriteAnalyticKeyGroups(ThreeKeyGroups(), 12, settings);
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  if (const char* out = std::getenv("MESHVID_WRITE_GOLDEN")) {
    std::ofstream(std::string(out) + "/sphere.planes.mvid", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes->data()), bytes->size());
  }
  const std::string golden_path = std::string(MESHVID_GOLDEN_DIR) + "/sphere.planes.mvid";
  for (const bool golden : {false, true}) {
    auto reader = golden ? ContainerReader::OpenFile(golden_path)
                         : ContainerReader::OpenMemory(*bytes);
    ASSERT_TRUE(reader.ok()) << reader.status().ToString();
    auto gof = reader->ReadGof(0);
    ASSERT_TRUE(gof.ok()) << gof.status().ToString();
    ASSERT_FALSE(gof->transforms.empty());
    EXPECT_EQ(gof->transforms[0], 2) << "side_info_version, golden " << golden;
    auto decoder = golden ? MvidDecoder::OpenFile(golden_path) : MvidDecoder::OpenMemory(*bytes);
    ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
    EXPECT_EQ((*decoder)->info().key_groups.size(), 3u);
    EXPECT_LE(MaxError(**decoder, 2, 12), kStep / 2 * 1.01f + 1e-6f) << "golden " << golden;
  }
}

// tests/golden/sphere.colour.mvid: a colour stream (spec/mvid-codec.md 2.8), FFV1, two key
// groups; written by this test when MESHVID_WRITE_GOLDEN names a folder, decoded by it always.
// FFV1 is lossless, so a colour differs from the exact one by the 8-bit Y Cb Cr round trip.
TEST(MvidGoldenTest, ColourStreamFileDecodes) {
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.levels = 2;
  settings.gof_size = 3;
  settings.colour = true;
  settings.metadata_json = R"({"golden":"sphere colour"})";
  const TriangleMesh sphere = testing::SphereMesh(2);
  auto bytes = testing::WriteAnalyticKeyGroups({{sphere, 0}, {sphere, 4}}, 7, settings);
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  if (const char* out = std::getenv("MESHVID_WRITE_GOLDEN")) {
    std::ofstream(std::string(out) + "/sphere.colour.mvid", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes->data()), bytes->size());
  }
  for (const bool golden : {false, true}) {
    auto decoder =
        golden ? MvidDecoder::OpenFile(std::string(MESHVID_GOLDEN_DIR) + "/sphere.colour.mvid")
               : MvidDecoder::OpenMemory(*bytes);
    ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
    EXPECT_TRUE((*decoder)->info().colour);
    EXPECT_EQ((*decoder)->info().key_groups.size(), 2u);
    for (int level = 0; level <= 2; ++level) {
      auto error = testing::MaxColourError(**decoder, level, 7);
      ASSERT_TRUE(error.ok()) << error.status().ToString();
      EXPECT_LE(*error, 2) << "level " << level << ", golden " << golden;
    }
    EXPECT_LE(MaxError(**decoder, 2, 7), kStep / 2 * 1.01f + 1e-6f) << "golden " << golden;
    auto mesh = (*decoder)->DecodeFrame(5, 1);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    EXPECT_EQ(mesh->colours.size(), mesh->vertex_count());
  }
}

}  // namespace
}  // namespace meshvid
