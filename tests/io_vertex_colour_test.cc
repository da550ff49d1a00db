// Per-vertex colour through the mesh I/O module (PLY red/green/blue as uchar, ushort, float
// and double; OBJ `v x y z r g b`) and through the mesh operations that add or drop vertices.
#include <bit>
#include <cstring>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_util.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << (text) << "\n  lacks: " << (part)

// A quad of two triangles with a colour per vertex, channels at both ends of their range.
TriangleMesh MakeColouredMesh() {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.triangles = {Triangle(0, 1, 2), Triangle(0, 2, 3)};
  mesh.colours = {Colour(255, 0, 0), Colour(0, 255, 1), Colour(17, 128, 254), Colour(0, 0, 0)};
  return mesh;
}

StatusOr<TriangleMesh> ParsePlyString(const std::string& text) {
  std::istringstream in(text);
  return ReadPly(in, "test.ply");
}

StatusOr<TriangleMesh> ParseObjString(const std::string& text) {
  std::istringstream in(text);
  return ReadObj(in, "test.obj");
}

void ExpectColours(const TriangleMesh& mesh, const std::vector<Colour>& colours) {
  ASSERT_EQ(mesh.colours.size(), colours.size());
  for (std::size_t i = 0; i < colours.size(); ++i) {
    EXPECT_EQ(mesh.colours[i], colours[i]) << "vertex " << i;
  }
}

void ExpectError(const StatusOr<TriangleMesh>& result, const std::string& file,
                 const std::string& problem) {
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().message().rfind(file + ": ", 0), 0u) << result.status().message();
  EXPECT_CONTAINS(result.status().message(), problem);
}

// Little-endian bytes of `value`.
template <typename T>
std::string LittleEndian(T value) {
  static_assert(std::endian::native == std::endian::little);
  std::string bytes(sizeof(T), '\0');
  std::memcpy(bytes.data(), &value, sizeof(T));
  return bytes;
}

TEST(VertexColourTest, PlyRoundTripsInBinaryAndAscii) {
  const TriangleMesh mesh = MakeColouredMesh();
  for (const PlyEncoding encoding : {PlyEncoding::kBinaryLittleEndian, PlyEncoding::kAscii}) {
    std::ostringstream out;
    MeshWriteOptions options;
    options.ply_encoding = encoding;
    ASSERT_TRUE(WritePly(out, mesh, options).ok());
    EXPECT_CONTAINS(out.str(), "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    const auto read = ParsePlyString(out.str());
    ASSERT_TRUE(read.ok()) << read.status().ToString();
    ExpectColours(*read, mesh.colours);
    EXPECT_EQ(read->positions, mesh.positions);
  }
  // Asked not to, the writer leaves them out.
  std::ostringstream out;
  MeshWriteOptions options;
  options.write_colours = false;
  ASSERT_TRUE(WritePly(out, mesh, options).ok());
  EXPECT_EQ(out.str().find("red"), std::string::npos);
}

TEST(VertexColourTest, PlyReadsFloatDoubleAndUshortChannelsAsEightBits) {
  // Ascii, float channels in [0, 1] among other properties, alpha skipped.
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
      "property float alpha\nelement face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n0 0 0 0 0.5 1 1\n1 0 0 0.2 0.4 0.6 1\n0 1 0 1 1 1 0\n3 0 1 2\n";
  auto read = ParsePlyString(ascii);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ExpectColours(*read, {Colour(0, 128, 255), Colour(51, 102, 153), Colour(255, 255, 255)});

  // Binary, fixed rows: double red, ushort green, uchar blue (diffuse_ names).
  std::string body;
  const double reds[3] = {0.0, 1.0, 0.5};
  const std::uint16_t greens[3] = {0, 65535, 257 * 40};
  const std::uint8_t blues[3] = {3, 200, 99};
  for (int v = 0; v < 3; ++v) {
    body += LittleEndian(float(v)) + LittleEndian(0.0f) + LittleEndian(float(v % 2));
    body += LittleEndian(reds[v]) + LittleEndian(greens[v]) + LittleEndian(blues[v]);
  }
  body += std::string(1, '\3') + LittleEndian(std::int32_t(0)) + LittleEndian(std::int32_t(1)) +
          LittleEndian(std::int32_t(2));
  const std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nproperty double diffuse_red\n"
      "property ushort diffuse_green\nproperty uchar diffuse_blue\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n" +
      body;
  read = ParsePlyString(binary);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ExpectColours(*read, {Colour(0, 0, 3), Colour(255, 255, 200), Colour(128, 40, 99)});
}

TEST(VertexColourTest, PlyWithoutAllThreeChannelsHasNoColours) {
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nproperty uchar green\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0 1 2\n1 0 0 3 4\n0 1 0 5 6\n"
      "3 0 1 2\n";
  const auto read = ParsePlyString(ascii);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_TRUE(read->colours.empty());
}

TEST(VertexColourTest, PlyBadColoursAreErrorsNamingTheFileAndVertex) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  ExpectError(ParsePlyString(header + "0 0 0 0 0 0\n1 0 0 0 1.5 0\n0 1 0 0 0 0\n3 0 1 2\n"),
              "test.ply",
              "vertex 1 has colour channel 1.5, which must be in [0, 1] for a floating-point "
              "channel");
  ExpectError(ParsePlyString(header + "0 0 0 0 0 0\n1 0 0 0 0 0\n0 1 0 -0.25 0 0\n3 0 1 2\n"),
              "test.ply", "vertex 2 has colour channel -0.25");
  ExpectError(ParsePlyString(header + "0 0 0 nan 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n"),
              "test.ply", "vertex 0 has colour channel");
  // A short row is the reader's usual error.
  ExpectError(ParsePlyString(header + "0 0 0 0 0 0\n1 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n"), "test.ply",
              "vertex 1: too few values on the line");
  // Integer channels must be whole numbers in their range (an ascii file can hold anything).
  const std::string uchar_header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  ExpectError(ParsePlyString(uchar_header + "0 0 0 1 2 3\n1 0 0 300 0 0\n0 1 0 0 0 0\n3 0 1 2\n"),
              "test.ply",
              "vertex 1 has colour channel 300, which must be a whole number in 0..255 for an "
              "integer channel");
  ExpectError(ParsePlyString(uchar_header + "0 0 0 1 2.5 3\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n"),
              "test.ply", "vertex 0 has colour channel 2.5");
  ExpectError(ParsePlyString(uchar_header + "0 0 0 1 2 3\n1 0 0 0 0 0\n0 1 0 0 0 -1\n3 0 1 2\n"),
              "test.ply", "vertex 2 has colour channel -1");
  // Other integer types hold 0..255 too.
  const std::string int_colour =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty int red\nproperty short green\nproperty uint blue\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 1 2 3\n1 0 0 255 0 9\n0 1 0 0 0 0\n3 0 1 2\n";
  const auto ints = ParsePlyString(int_colour);
  ASSERT_TRUE(ints.ok()) << ints.status().ToString();
  ExpectColours(*ints, {Colour(1, 2, 3), Colour(255, 0, 9), Colour(0, 0, 0)});
  // A list is not a channel.
  const std::string list_colour =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty list uchar uchar red\nproperty uchar green\n"
      "property uchar blue\nelement face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n";
  const auto read = ParsePlyString(list_colour);
  ExpectError(read, "test.ply", "vertex colour property 'red' is a list");
  EXPECT_EQ(read.status().code(), StatusCode::kUnsupported);
}

TEST(VertexColourTest, PlyColoursInBinaryRowsWithListsAndInRangeGrids) {
  // A binary vertex element with a list property is read row by row, not by the fixed-row
  // fast path.
  std::string body;
  for (int v = 0; v < 3; ++v) {
    body += LittleEndian(float(v == 1)) + LittleEndian(float(v == 2)) + LittleEndian(0.0f);
    body += LittleEndian(std::uint8_t(10 * v)) + LittleEndian(std::uint8_t(20 * v)) +
            LittleEndian(std::uint8_t(30 * v));
    body += std::string(1, '\1') + LittleEndian(0.5f);  // a list of one float
  }
  body += std::string(1, '\3') + LittleEndian(std::int32_t(0)) + LittleEndian(std::int32_t(1)) +
          LittleEndian(std::int32_t(2));
  const std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nproperty list uchar float weights\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n" +
      body;
  auto read = ParsePlyString(binary);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ExpectColours(*read, {Colour(0, 0, 0), Colour(10, 20, 30), Colour(20, 40, 60)});

  // A Stanford range grid's vertices keep their colours through its meshing.
  const std::string grid =
      "ply\nformat ascii 1.0\nobj_info num_cols 2\nobj_info num_rows 2\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\nproperty uchar red\n"
      "property uchar green\nproperty uchar blue\nelement range_grid 4\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 0 1 1 0 0\n1 0 1 2 0 0\n0 1 1 3 0 0\n1 1 1 4 0 0\n1 0\n1 1\n1 2\n1 3\n";
  read = ParsePlyString(grid);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ASSERT_EQ(read->colours.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    // Red numbers the file's vertex: 1 + x + 2 y.
    const Eigen::Vector3f& p = read->positions[i];
    EXPECT_EQ(read->colours[i][0], 1 + std::lround(p.x()) + 2 * std::lround(p.y())) << i;
  }
}

TEST(VertexColourTest, ObjRoundTripsAndReadsChannelsInZeroToOne) {
  const TriangleMesh mesh = MakeColouredMesh();
  std::ostringstream out;
  ASSERT_TRUE(WriteObj(out, mesh, {}).ok());
  EXPECT_CONTAINS(out.str(), "v 0 0 0 1 0 0\n");
  auto read = ParseObjString(out.str());
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ExpectColours(*read, mesh.colours);

  read = ParseObjString("v 0 0 0 0 0.5 1\nv 1 0 0 0.2 0.4 0.6\nv 0 1 0 1 1 1\nf 1 2 3\n");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ExpectColours(*read, {Colour(0, 128, 255), Colour(51, 102, 153), Colour(255, 255, 255)});
  // A `w`, or more than three numbers after the position, is not a colour.
  for (const char* extra : {" 1", " 1 0.5", " 1 0.5 0.5 0.5"}) {
    const std::string v = std::string(extra) + "\n";
    read = ParseObjString("v 0 0 0" + v + "v 1 0 0" + v + "v 0 1 0" + v + "f 1 2 3\n");
    ASSERT_TRUE(read.ok()) << read.status().ToString();
    EXPECT_TRUE(read->colours.empty()) << extra;
  }
}

TEST(VertexColourTest, ObjBadColoursAreErrorsNamingTheFileAndLine) {
  ExpectError(ParseObjString("v 0 0 0 0 0 0\nv 1 0 0 0 255 0\nv 0 1 0 0 0 0\nf 1 2 3\n"),
              "test.obj", "line 2: vertex colour channel 255");
  ExpectError(ParseObjString("v 0 0 0 0 0 0\nv 1 0 0\nv 0 1 0 0 0 0\nf 1 2 3\n"), "test.obj",
              "line 2: no vertex colour, but the 'v' line at line 1 has one");
  ExpectError(ParseObjString("# uncoloured first\nv 0 0 0\nv 1 0 0 1 1 1\nv 0 1 0\nf 1 2 3\n"),
              "test.obj", "line 3: a vertex colour, but the 'v' line at line 2 has none");
  ExpectError(ParseObjString("v 0 0 0 0 red 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "test.obj",
              "line 1: 'red' is not a number");
}

TEST(VertexColourTest, MeshOperationsKeepColoursWithTheirVertices) {
  TriangleMesh mesh = MakeColouredMesh();
  EXPECT_TRUE(ValidateMesh(mesh, "m").ok());
  TriangleMesh short_colours = mesh;
  short_colours.colours.pop_back();
  EXPECT_FALSE(ValidateMesh(short_colours, "m").ok());

  // Appending keeps colours only where both meshes have them.
  TriangleMesh both = mesh;
  AppendMesh(mesh, &both);
  ASSERT_EQ(both.colours.size(), 8u);
  EXPECT_EQ(both.colours[6], mesh.colours[2]);
  TriangleMesh plain = mesh;
  plain.colours.clear();
  AppendMesh(mesh, &plain);
  EXPECT_TRUE(plain.colours.empty());
  EXPECT_TRUE(ValidateMesh(plain, "m").ok());
  TriangleMesh coloured = mesh;
  TriangleMesh uncoloured = mesh;
  uncoloured.colours.clear();
  AppendMesh(uncoloured, &coloured);
  EXPECT_TRUE(coloured.colours.empty());
  EXPECT_TRUE(ValidateMesh(coloured, "m").ok());

  // Dropping an unused vertex drops its colour; the others follow their new numbers.
  TriangleMesh unused = mesh;
  unused.triangles = {Triangle(3, 1, 2)};
  RemoveUnreferencedVertices(&unused);
  ExpectColours(unused, {mesh.colours[3], mesh.colours[1], mesh.colours[2]});

  // A vertex split where two fans meet keeps its colour in the copy.
  TriangleMesh bowtie;
  bowtie.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  bowtie.triangles = {Triangle(0, 1, 2), Triangle(0, 3, 4)};
  bowtie.colours = {Colour(9, 9, 9), Colour(1, 0, 0), Colour(2, 0, 0), Colour(3, 0, 0),
                    Colour(4, 0, 0)};
  ASSERT_EQ(SplitNonManifoldVertices(&bowtie), 1u);
  ExpectColours(bowtie, {Colour(9, 9, 9), Colour(1, 0, 0), Colour(2, 0, 0), Colour(3, 0, 0),
                         Colour(4, 0, 0), Colour(9, 9, 9)});
  EXPECT_TRUE(ValidateMesh(bowtie, "m").ok());
}

}  // namespace
}  // namespace meshvid
