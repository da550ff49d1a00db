// Detail edits (codec/enc/coding/detail_edit.h): a sculpted frame becomes a change of the
// displacement field that every frame of its key group takes, and nothing else changes.
#include "codec/enc/coding/detail_edit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "codec/dec/mvid_decoder.h"
#include "tests/analytic_mvid.h"
#include "tests/test_util.h"

namespace meshvid {
namespace {

using testing::MakeGridPlane;

/// A flat base (normals +z) subdivided twice, and its level-1 samples' frames.
struct FlatLattice {
  TriangleMesh base = MakeGridPlane(1.0f, 4);
  RegularSubdivision lattice = RegularSubdivision::Create(base, 2).value();
  std::vector<Eigen::Vector3f> origins, directions;

  explicit FlatLattice(int level) {
    std::vector<Eigen::Vector3f> normals;
    ComputeVertexNormals(base.positions, base.triangles, &normals);
    EvaluateSampleFrames(lattice, level, base.positions, normals, &origins, &directions);
  }
};

TEST(DetailChangeTest, AVertexMovedAlongItsNormalChangesItsSampleAndFinerOnesAroundIt) {
  const FlatLattice flat(1);
  // The level-1 sample nearest the middle, moved up by 0.01 and sideways by 0.003.
  std::size_t moved = 0;
  for (std::size_t s = 0; s < flat.origins.size(); ++s) {
    if (flat.origins[s].norm() < flat.origins[moved].norm()) moved = s;
  }
  std::vector<Eigen::Vector3f> edited = flat.origins;
  edited[moved] += Eigen::Vector3f(0.003f, 0, 0.01f);
  auto change = DetailChangeFromPositions(flat.lattice, 1, flat.origins, flat.directions, edited);
  ASSERT_TRUE(change.ok()) << change.status().ToString();
  EXPECT_EQ(change->moved_vertices, 1u);
  EXPECT_NEAR(change->largest_normal_move, 0.01, 1e-6);
  EXPECT_NEAR(change->largest_tangential_move, 0.003, 1e-6);
  ASSERT_EQ(change->change.size(), flat.lattice.samples().size());

  // The finest samples: the level-1 hat function of the moved sample, times 0.01.
  const FlatLattice finest(2);
  const Eigen::Vector3f centre = flat.origins[moved];
  const float spacing = 1.0f / 8;  // level 1 on a 4x4 grid of side 1
  int halfway = 0;
  for (std::size_t s = 0; s < finest.origins.size(); ++s) {
    const Eigen::Vector3f d = finest.origins[s] - centre;
    const float c = change->change[s];
    EXPECT_GE(c, -1e-7f) << s;
    EXPECT_LE(c, 0.01f + 1e-7f) << s;
    if (s == moved) {
      EXPECT_FLOAT_EQ(c, 0.01f);
    }
    // Beyond the moved sample's level-1 triangles nothing changes.
    if (std::max(std::abs(d.x()), std::abs(d.y())) > spacing + 1e-5f) {
      EXPECT_EQ(c, 0.0f) << s;
    }
    // Half a level-1 edge away along an axis: half the move.
    if (std::abs(d.norm() - spacing / 2) < 1e-5f &&
        (std::abs(d.x()) < 1e-5f || std::abs(d.y()) < 1e-5f)) {
      EXPECT_NEAR(c, 0.005f, 1e-6f) << s;
      ++halfway;
    }
  }
  EXPECT_EQ(halfway, 4);
}

TEST(DetailChangeTest, EditsThatAreNotTheFrameAreRefused) {
  const FlatLattice flat(1);
  std::vector<Eigen::Vector3f> short_one(flat.origins.begin(), flat.origins.end() - 1);
  auto wrong_size =
      DetailChangeFromPositions(flat.lattice, 1, flat.origins, flat.directions, short_one);
  EXPECT_EQ(wrong_size.status().code(), StatusCode::kInvalidArgument);
  std::vector<Eigen::Vector3f> not_finite = flat.origins;
  not_finite[3].z() = std::numeric_limits<float>::quiet_NaN();
  auto nan = DetailChangeFromPositions(flat.lattice, 1, flat.origins, flat.directions, not_finite);
  EXPECT_EQ(nan.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(nan.status().ToString().find("vertex 3"), std::string::npos) << nan.status().ToString();
}

/// An FFV1 (lossless video) analytic file with colour and two key groups (frames 0-3 and 4-6,
/// groups of up to 3 frames), written to `path`.
void WriteTwoKeyGroupFile(const std::string& path) {
  MvidWriterSettings settings;
  settings.codec = VideoCodec::kFfv1;
  settings.levels = 2;
  settings.gof_size = 3;
  settings.colour = true;
  const TriangleMesh sphere = testing::SphereMesh(2);
  auto bytes = testing::WriteAnalyticKeyGroups({{sphere, 0}, {sphere, 4}}, 7, settings);
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes->data()), std::streamsize(bytes->size()));
}

/// Frame `frame` at `level` of `path`, its vertex `vertex` moved by `bump` along the line from
/// the origin (the sphere's outward normal, near enough).
std::vector<Eigen::Vector3f> Bumped(const std::string& path, std::uint32_t frame, int level,
                                    std::size_t vertex, float bump) {
  auto decoder = MvidDecoder::OpenFile(path);
  EXPECT_TRUE(decoder.ok());
  std::vector<Eigen::Vector3f> positions;
  EXPECT_TRUE((*decoder)->DecodePositions(frame, level, &positions).ok());
  positions[vertex] += bump * positions[vertex].normalized();
  return positions;
}

TEST(DetailEditTest, ABumpRidesEveryFrameOfItsKeyGroupAndNothingElseChanges) {
  testing::TempDir dir;
  const std::string input = dir.File("in.mvid"), output = dir.File("out.mvid");
  WriteTwoKeyGroupFile(input);
  constexpr std::size_t kVertex = 5;
  for (const float bump : {0.005f, 0.05f}) {  // within the displacement range, and beyond it
    SCOPED_TRACE(bump);
    DetailEditOptions options;
    options.frame = 1;
    options.level = 1;
    options.edited = Bumped(input, 1, 1, kVertex, bump);
    auto summary = EditDetail(input, output, options);
    ASSERT_TRUE(summary.ok()) << summary.status().ToString();
    EXPECT_EQ(summary->key_group, 0u);
    EXPECT_EQ(summary->first_frame, 0u);
    EXPECT_EQ(summary->frame_count, 4u);
    EXPECT_EQ(summary->groups_coded, 2u);
    EXPECT_EQ(summary->change.moved_vertices, 1u);
    EXPECT_EQ(summary->ranges_widened, bump > 0.03f ? 2u : 0u);

    auto before = MvidDecoder::OpenFile(input);
    auto after = MvidDecoder::OpenFile(output);
    ASSERT_TRUE(before.ok() && after.ok());
    std::vector<float> a, b;
    for (std::uint32_t f = 0; f < 7; ++f) {
      ASSERT_TRUE((*before)->DecodeDisplacements(f, &a).ok());
      ASSERT_TRUE((*after)->DecodeDisplacements(f, &b).ok());
      ASSERT_EQ(a.size(), b.size());
      if (f < 4) {
        // The bump, in every frame of the key group, along that frame's own normal.
        // (The bump is radial; the sample's direction, an interpolated normal, is a few
        // degrees off it.)
        EXPECT_NEAR(b[kVertex] - a[kVertex], bump, 0.02f * bump + 2e-4f) << "frame " << f;
      } else {
        EXPECT_EQ(a, b) << "frame " << f << " is in the other key group";
      }
    }
    // Colour is copied as it was.
    std::vector<Colour> colours_before, colours_after;
    ASSERT_TRUE((*before)->DecodeColours(2, 2, &colours_before).ok());
    ASSERT_TRUE((*after)->DecodeColours(2, 2, &colours_after).ok());
    EXPECT_EQ(colours_before, colours_after);
  }
}

TEST(DetailEditTest, UnchangedSamplesKeepTheirValuesWhenTheRangeHoldsTheEdit) {
  testing::TempDir dir;
  const std::string input = dir.File("in.mvid"), output = dir.File("out.mvid");
  WriteTwoKeyGroupFile(input);
  // The base vertex whose detail stays nearest 0 over the key group's frames, bumped by
  // 0.004: well inside the groups' ranges (the detail spans about +-0.02).
  auto before = MvidDecoder::OpenFile(input);
  ASSERT_TRUE(before.ok());
  const std::size_t base_vertices = (*before)->info().vertices_per_level[0];
  std::vector<float> largest(base_vertices, 0.0f), field;
  for (std::uint32_t f = 0; f < 4; ++f) {
    ASSERT_TRUE((*before)->DecodeDisplacements(f, &field).ok());
    for (std::size_t v = 0; v < base_vertices; ++v) {
      largest[v] = std::max(largest[v], std::abs(field[v]));
    }
  }
  const std::size_t vertex = std::min_element(largest.begin(), largest.end()) - largest.begin();
  DetailEditOptions options;
  options.frame = 2;
  options.level = 0;  // a base vertex: the change spreads over its one-ring's finer samples
  options.edited = Bumped(input, 2, 0, vertex, 0.004f);
  auto summary = EditDetail(input, output, options);
  ASSERT_TRUE(summary.ok()) << summary.status().ToString();
  ASSERT_EQ(summary->ranges_widened, 0u);
  auto after = MvidDecoder::OpenFile(output);
  ASSERT_TRUE(after.ok());
  std::vector<float> a, b;
  ASSERT_TRUE((*before)->DecodeDisplacements(3, &a).ok());
  ASSERT_TRUE((*after)->DecodeDisplacements(3, &b).ok());
  std::size_t changed = 0;
  for (std::size_t s = 0; s < a.size(); ++s) changed += a[s] != b[s];
  EXPECT_NEAR(b[vertex] - a[vertex], 0.004f, 2e-4f);
  // FFV1 is lossless and the range unchanged: only the bump's samples differ.
  EXPECT_GT(changed, 1u);
  EXPECT_LT(changed, a.size() / 10);
}

TEST(DetailEditTest, BadEditsAreClearErrors) {
  testing::TempDir dir;
  const std::string input = dir.File("in.mvid"), output = dir.File("out.mvid");
  WriteTwoKeyGroupFile(input);
  DetailEditOptions options;
  options.frame = 1;
  options.level = 1;
  options.edited = Bumped(input, 1, 1, 0, 0.01f);
  options.edited.pop_back();
  auto wrong_size = EditDetail(input, output, options);
  EXPECT_EQ(wrong_size.status().code(), StatusCode::kInvalidArgument);
  options.edited = Bumped(input, 1, 1, 0, 0.01f);
  options.frame = 7;
  auto past_the_end = EditDetail(input, output, options);
  EXPECT_EQ(past_the_end.status().code(), StatusCode::kInvalidArgument);
  options.frame = 1;
  auto onto_itself = EditDetail(input, input, options);
  EXPECT_EQ(onto_itself.status().code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(std::ifstream(output).good()) << "nothing is written on failure";
}

}  // namespace
}  // namespace meshvid
