// Colour end to end: a simulated capture with colour encodes to a file with a colour stream,
// `meshvid info` lists it, and `meshvid decode` writes vertex colours close to the ground
// truth's; --no-colour writes the geometry-only file.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "codec/common/triangle_distance.h"
#include "tests/test_util.h"
#include "tools/io/capture.h"
#include "tools/io/mesh_io.h"
#include "tools/io/mesh_sequence.h"

namespace meshvid {
namespace {

/// The colour of `mesh` at its surface point nearest `p` (brute force).
Eigen::Vector3f ColourNearest(const TriangleMesh& mesh, const Eigen::Vector3f& p) {
  float best = std::numeric_limits<float>::infinity();
  Eigen::Vector3f colour = Eigen::Vector3f::Zero();
  for (const Triangle& t : mesh.triangles) {
    const Eigen::Vector3f &a = mesh.positions[t[0]], &b = mesh.positions[t[1]],
                          &c = mesh.positions[t[2]];
    const Eigen::Vector3f q = ClosestPointOnTriangle(p, a, b, c);
    const float distance = (q - p).squaredNorm();
    if (!(distance < best)) continue;
    best = distance;
    const Eigen::Vector3f w = BarycentricWeights(q, a, b, c);
    colour = w[0] * mesh.colours[t[0]].cast<float>() + w[1] * mesh.colours[t[1]].cast<float>() +
             w[2] * mesh.colours[t[2]].cast<float>();
  }
  return colour;
}

/// The mean absolute difference, over every 7th vertex of `mesh` and its three channels,
/// between its colour and `truth`'s at the nearest surface point.
double MeanColourError(const TriangleMesh& mesh, const TriangleMesh& truth) {
  EXPECT_EQ(mesh.colours.size(), mesh.vertex_count());
  double error = 0;
  int count = 0;
  for (std::size_t i = 0; i < mesh.colours.size(); i += 7) {
    error +=
        (mesh.colours[i].cast<float>() - ColourNearest(truth, mesh.positions[i])).cwiseAbs().sum() /
        3.0;
    ++count;
  }
  EXPECT_GT(count, 100);
  return count > 0 ? error / count : 0;
}

TEST(ColourCliTest, ACapturesColourIsCodedAndDecoded) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  testing::CliRun run = testing::RunMeshvid(
      "simulate scene:arm-block -o '" + dir.File("cap") + "' --frames 0:4 --res 160x120 -q ", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string encode = "encode '" + dir.File("cap/manifest.json") + "' -q ";
  run = testing::RunMeshvid(encode + "-o '" + dir.File("colour.mvid") + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = testing::RunMeshvid(encode + "--no-colour -o '" + dir.File("grey.mvid") + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;

  run = testing::RunMeshvid("info --check --json - '" + dir.File("colour.mvid") + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json info = nlohmann::json::parse(run.out);
  EXPECT_EQ(info["colour"], true);
  EXPECT_GT(info["bytes"]["colour"].get<double>(), 0);
  run = testing::RunMeshvid("info --json - '" + dir.File("grey.mvid") + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["colour"], false);

  // Frame 2 at level 2, against the ground truth's colour where each vertex lies.
  run = testing::RunMeshvid("decode '" + dir.File("colour.mvid") + "' --frames 2:3 --level 2 -q -o '" +
                                dir.File("f{frame}.ply") + "'",
                            dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  auto decoded = ReadMesh(dir.File("f2.ply"));
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  ASSERT_EQ(decoded->colours.size(), decoded->vertex_count());
  auto truth = OpenMeshSequence(dir.File("cap/ground_truth.obj"));
  ASSERT_TRUE(truth.ok()) << truth.status().ToString();
  auto frame = (*truth)->Frame(2);
  ASSERT_TRUE(frame.ok());
  ASSERT_FALSE(frame->colours.empty());
  // The views' own colour, each on its own exposure and with its own noise, is the input's
  // error; the decoded colour, fused on one exposure, is to be much closer to the truth (here
  // 6.4 units against the views' 18.8; with neither exposure spread nor noise, the views are
  // 0.8 units off and the decoded frame 6.2: what the coding and the sampling cost at
  // 160 x 120).
  auto capture = CaptureSequence::Open(dir.File("cap/manifest.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  auto views = (*capture)->LoadFrame(2);
  ASSERT_TRUE(views.ok()) << views.status().ToString();
  double view_error = 0;
  for (const TriangleMesh& view : *views) view_error += MeanColourError(view, *frame);
  view_error /= views->size();
  const double decoded_error = MeanColourError(*decoded, *frame);
  std::printf("mean colour error against the truth, units of 8 bits: views %.2f, decoded %.2f\n",
              view_error, decoded_error);
  EXPECT_LT(decoded_error, 0.5 * view_error);

  // Export: the OBJ of a key group holds its first frame's colours (OBJ + PC2 cannot animate
  // them), and glTF its base vertices' as COLOR_0.
  run = testing::RunMeshvid(
      "export '" + dir.File("colour.mvid") + "' --frames 2:3 -q -o '" + dir.File("x.obj") + "'",
      dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  auto exported = ReadMesh(dir.File("x.obj"));
  ASSERT_TRUE(exported.ok()) << exported.status().ToString();
  ASSERT_EQ(exported->colours.size(), exported->vertex_count());
  EXPECT_EQ(exported->colours, decoded->colours);  // frame 2 at the finest level, as decoded
  run = testing::RunMeshvid(
      "export '" + dir.File("colour.mvid") + "' -q -o '" + dir.File("x.glb") + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(testing::ReadFile(dir.File("x.glb")).find("\"COLOR_0\""), std::string::npos);

  // The geometry-only file decodes without colour.
  run = testing::RunMeshvid("decode '" + dir.File("grey.mvid") + "' --frames 2:3 --level 2 -q -o '" +
                                dir.File("g{frame}.ply") + "'",
                            dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  auto grey = ReadMesh(dir.File("g2.ply"));
  ASSERT_TRUE(grey.ok());
  EXPECT_TRUE(grey->colours.empty());
  // Colour costs the geometry nothing: the same triangles and positions, bit for bit.
  EXPECT_EQ(grey->triangles, decoded->triangles);
  EXPECT_EQ(grey->positions, decoded->positions);
}

}  // namespace
}  // namespace meshvid
