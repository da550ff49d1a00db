// PLY reader and writer: round trips in every encoding, hand-written files (polygons, skipped
// properties and elements, range grids) and every error the reader reports.
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_util.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

// Asserts that `text` contains `part`, printing both otherwise.
#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << (text) << "\n  lacks: " << (part)

// A small mesh with awkward floats (not exactly representable in short decimals).
TriangleMesh MakeAwkwardMesh() {
  TriangleMesh mesh;
  mesh.positions = {{0.1f, 1.0f / 3.0f, -2.5e-7f},
                    {12345.678f, -0.7f, 3.14159265f},
                    {-1.0e6f, 2.0f / 7.0f, 1.0e-3f},
                    {5.0f, 6.0f, -7.125f}};
  mesh.triangles = {Triangle(0, 1, 2), Triangle(0, 2, 3), Triangle(3, 2, 1)};
  mesh.normals = {{0, 0, 1}, {0.6f, 0.8f, 0}, {1.0f / std::sqrt(3.0f), -1.0f / std::sqrt(3.0f), 0.57735f},
                  {0, -1, 0}};
  return mesh;
}

void ExpectSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  ASSERT_EQ(a.normals.size(), b.normals.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_EQ(a.positions[i], b.positions[i]) << "vertex " << i;
  }
  for (std::size_t i = 0; i < a.normals.size(); ++i) {
    EXPECT_EQ(a.normals[i], b.normals[i]) << "normal " << i;
  }
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    EXPECT_EQ(a.triangles[i], b.triangles[i]) << "triangle " << i;
  }
}

StatusOr<TriangleMesh> ParseString(const std::string& text) {
  std::istringstream in(text);
  return ReadPly(in, "test.ply");
}

// Builds binary PLY bodies value by value in either byte order.
class Bytes {
 public:
  explicit Bytes(bool big_endian) : big_endian_(big_endian) {}
  template <typename T>
  Bytes& Put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (big_endian_ != (std::endian::native == std::endian::big)) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    }
    data_.append(raw, sizeof(T));
    return *this;
  }
  const std::string& str() const { return data_; }

 private:
  bool big_endian_;
  std::string data_;
};

void ExpectError(const StatusOr<TriangleMesh>& result, StatusCode code,
                 const std::string& problem) {
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), code) << result.status().ToString();
  EXPECT_EQ(result.status().message().rfind("test.ply: ", 0), 0u) << result.status().message();
  EXPECT_CONTAINS(result.status().message(), (problem));
}

TEST(PlyTest, BinaryRoundTripIsExact) {
  const TriangleMesh mesh = MakeAwkwardMesh();
  std::ostringstream out;
  ASSERT_TRUE(WritePly(out, mesh, {}).ok());
  EXPECT_CONTAINS(out.str(), ("format binary_little_endian 1.0\n"));
  EXPECT_CONTAINS(out.str(), ("property list uchar int vertex_indices\n"));
  const auto read = ParseString(out.str());
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ExpectSameMesh(mesh, *read);
}

TEST(PlyTest, AsciiRoundTripIsExact) {
  const TriangleMesh mesh = MakeAwkwardMesh();
  std::ostringstream out;
  MeshWriteOptions options;
  options.ply_encoding = PlyEncoding::kAscii;
  ASSERT_TRUE(WritePly(out, mesh, options).ok());
  EXPECT_CONTAINS(out.str(), ("format ascii 1.0\n"));
  const auto read = ParseString(out.str());
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ExpectSameMesh(mesh, *read);
}

TEST(PlyTest, WriteWithoutNormalsDropsThem) {
  std::ostringstream out;
  MeshWriteOptions options;
  options.write_normals = false;
  ASSERT_TRUE(WritePly(out, MakeAwkwardMesh(), options).ok());
  EXPECT_EQ(out.str().find("nx"), std::string::npos);
  const auto read = ParseString(out.str());
  ASSERT_TRUE(read.ok());
  EXPECT_TRUE(read->normals.empty());
  EXPECT_EQ(read->positions, MakeAwkwardMesh().positions);
}

TEST(PlyTest, WriteRejectsInvalidMesh) {
  TriangleMesh mesh = MakeAwkwardMesh();
  mesh.triangles[1][2] = 9;
  std::ostringstream out;
  const Status status = WritePly(out, mesh, {});
  EXPECT_EQ(status.code(), StatusCode::kCorrupt);
  EXPECT_CONTAINS(status.message(), ("vertex index 9"));
}

TEST(PlyTest, BigEndianWithOtherTypesAndExtraElements) {
  Bytes body(/*big_endian=*/true);
  const float xyz[4][3] = {{1.5f, -2.25f, 0.1f}, {3, 4, 5}, {-6, 7.75f, 8}, {0.3f, 0.2f, 0.1f}};
  for (int v = 0; v < 4; ++v) {
    body.Put<std::uint8_t>(200).Put(xyz[v][0]).Put(xyz[v][1]);
    body.Put<std::int16_t>(-3).Put(xyz[v][2]);
    body.Put<std::uint8_t>(2).Put<double>(1.0).Put<double>(2.0);  // skipped list
  }
  body.Put<std::int32_t>(1).Put<std::int32_t>(2);  // one "edge" element row
  body.Put<std::uint8_t>(4).Put<std::uint16_t>(0).Put<std::uint16_t>(1)  // quad, ushort indices
      .Put<std::uint16_t>(2).Put<std::uint16_t>(3).Put<float>(0.5f);
  const std::string header =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty uchar red\n"
      "property float x\nproperty float y\nproperty short flags\nproperty float z\n"
      "property list uchar double weights\nelement edge 1\nproperty int vertex1\n"
      "property int vertex2\nelement face 1\nproperty list uint8 uint16 vertex_index\n"
      "property float quality\nend_header\n";
  const auto read = ParseString(header + body.str());
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ASSERT_EQ(read->positions.size(), 4u);
  for (int v = 0; v < 4; ++v) {
    EXPECT_EQ(read->positions[v], Eigen::Vector3f(xyz[v][0], xyz[v][1], xyz[v][2]));
  }
  ASSERT_EQ(read->triangles.size(), 2u);
  EXPECT_EQ(read->triangles[0], Triangle(0, 1, 2));
  EXPECT_EQ(read->triangles[1], Triangle(0, 2, 3));
  EXPECT_TRUE(read->normals.empty());
}

TEST(PlyTest, LittleEndianDoubleCoordinatesAndNormals) {
  Bytes body(/*big_endian=*/false);
  const double xyz[3][3] = {{0.1, 0.2, 0.3}, {1.0 / 3.0, 1e10, -4.0}, {7.0, 8.0, 9.5}};
  for (int v = 0; v < 3; ++v) {
    body.Put(xyz[v][0]).Put(xyz[v][1]).Put(xyz[v][2]);
    body.Put<float>(0).Put<float>(0).Put<float>(1);
  }
  body.Put<std::int8_t>(3).Put<std::uint32_t>(2).Put<std::uint32_t>(1).Put<std::uint32_t>(0);
  const std::string header =
      "ply\r\nformat binary_little_endian 1.0\r\ncomment made by hand\r\nobj_info hello\r\n"
      "element vertex 3\r\nproperty double x\r\nproperty double y\r\nproperty double z\r\n"
      "property float nx\r\nproperty float ny\r\nproperty float nz\r\nelement face 1\r\n"
      "property list char uint vertex_indices\r\nend_header\r\n";
  const auto read = ParseString(header + body.str());
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ASSERT_EQ(read->positions.size(), 3u);
  for (int v = 0; v < 3; ++v) {
    EXPECT_EQ(read->positions[v], Eigen::Vector3d(xyz[v][0], xyz[v][1], xyz[v][2]).cast<float>());
    EXPECT_EQ(read->normals[v], Eigen::Vector3f(0, 0, 1));
  }
  ASSERT_EQ(read->triangles.size(), 1u);
  EXPECT_EQ(read->triangles[0], Triangle(2, 1, 0));
}

TEST(PlyTest, AsciiPolygonsAreFanTriangulatedAndExtrasSkipped) {
  const std::string text =
      "ply\nformat ascii 1.0\ncomment a pentagon and a quad\nelement material 2\n"
      "property list uchar int ids\nproperty float shine\nelement vertex 6\n"
      "property float x\nproperty float y\nproperty float z\nproperty float nx\n"
      "property float ny\nproperty list int float extra\nelement face 2\n"
      "property int tag\nproperty list uchar int vertex_indices\nend_header\n"
      "3 1 2 3 0.5\n0 1.0\n"
      "0 0 0 9 9 0\n1 0 0 9 9 2 1 2\n1 1 0 9 9 0\n\n0 1 0 9 9 1 5\n0.5 2 0 9 9 0\n"
      "-1e2 +2 3.5 9 9 0   \n"
      "7 5 0 1 2 4 3\n8 4 1 2 5 0\n";
  const auto read = ParseString(text);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ASSERT_EQ(read->positions.size(), 6u);
  EXPECT_EQ(read->positions[5], Eigen::Vector3f(-100.0f, 2.0f, 3.5f));
  EXPECT_TRUE(read->normals.empty());  // nz is missing, so nx and ny are ignored
  const std::vector<Triangle> expected = {Triangle(0, 1, 2), Triangle(0, 2, 4), Triangle(0, 4, 3),
                                          Triangle(1, 2, 5), Triangle(1, 5, 0)};
  ASSERT_EQ(read->triangles.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(read->triangles[i], expected[i]);
}

TEST(PlyTest, RangeGridIsMeshedFacingTheScanner) {
  // 3 columns x 2 rows, rows stored bottom-up; the top-right sample is missing.
  const std::string text =
      "ply\nformat ascii 1.0\nobj_info num_cols 3\nobj_info num_rows 2\nelement vertex 5\n"
      "property float x\nproperty float y\nproperty float z\nelement range_grid 6\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0.001\n"
      "1 0\n1 1\n1 2\n1 3\n1 4\n0\n";
  const auto read = ParseString(text);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->positions.size(), 4u);  // sample 2 is only in the incomplete cell
  ASSERT_EQ(read->triangles.size(), 2u);
  for (std::size_t t = 0; t < read->triangles.size(); ++t) {
    EXPECT_GT(TriangleNormal(*read, t).z(), 0.99f) << "triangle " << t;
  }
}

TEST(PlyTest, FacesWinOverRangeGrid) {
  const std::string text =
      "ply\nformat ascii 1.0\nobj_info num_cols 2\nobj_info num_rows 2\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\nelement range_grid 4\n"
      "property list uchar int vertex_indices\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n1 1 0\n1 0\n1 1\n1 2\n1 3\n3 3 2 1\n";
  const auto read = ParseString(text);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ASSERT_EQ(read->triangles.size(), 1u);
  EXPECT_EQ(read->triangles[0], Triangle(3, 2, 1));
  EXPECT_EQ(read->positions.size(), 4u);
}

const char kAsciiHeader[] =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST(PlyErrorTest, MissingFile) {
  testing::TempDir dir;
  const std::string path = dir.File("absent.ply");
  const auto read = ReadMesh(path);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(read.status().message(), path + ": no such file");
}

TEST(PlyErrorTest, NotAPly) {
  ExpectError(ParseString("solid cube\nfacet normal 0 0 1\n"), StatusCode::kCorrupt,
              "not a PLY file");
  ExpectError(ParseString(""), StatusCode::kCorrupt, "not a PLY file");
}

TEST(PlyErrorTest, UnknownFormatAndType) {
  ExpectError(ParseString("ply\nformat binary_middle_endian 1.0\nend_header\n"),
              StatusCode::kUnsupported, "unknown PLY format 'binary_middle_endian'");
  ExpectError(ParseString("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n"
                          "end_header\n"),
              StatusCode::kCorrupt, "header line 4: unknown property type 'quad'");
  ExpectError(ParseString("ply\nformat ascii 1.0\nelement vertex 1\n"), StatusCode::kCorrupt,
              "no end_header");
}

TEST(PlyErrorTest, TruncatedBinaryVertices) {
  Bytes body(false);
  for (int i = 0; i < 7; ++i) body.Put<float>(1.0f);  // 2 vertices and a bit
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  ExpectError(ParseString(header + body.str()), StatusCode::kCorrupt,
              "truncated binary PLY: expected 4 vertex elements, file ends after 2");
}

TEST(PlyErrorTest, BinaryVerticesOneByteShortAreTruncatedNotReadPastTheEnd) {
  // Found by the fuzz smoke: 4 rows of 20 bytes in 79 bytes were let through by an ascii
  // allowance for a missing final newline, and the reader ran one byte past the buffer.
  Bytes body(true);
  for (int i = 0; i < 4; ++i) body.Put<double>(0.0).Put<double>(1.0).Put<std::uint32_t>(2);
  std::string bytes = body.str();
  bytes.pop_back();
  const std::string header =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty double x\n"
      "property double y\nproperty uint32 z\nelement face 0\n"
      "property list uchar int vertex_indices\nend_header\n";
  ExpectError(ParseString(header + bytes), StatusCode::kCorrupt,
              "truncated binary PLY: expected 4 vertex elements, file ends after 3");
}

TEST(PlyErrorTest, TruncatedBinaryFaces) {
  Bytes body(false);
  for (int i = 0; i < 9; ++i) body.Put<float>(static_cast<float>(i));
  body.Put<std::uint8_t>(3).Put<std::int32_t>(0).Put<std::int32_t>(1).Put<std::int32_t>(2);
  body.Put<std::uint8_t>(3).Put<std::int32_t>(0);
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 2\n"
      "property list uchar int vertex_indices\nend_header\n";
  ExpectError(ParseString(header + body.str()), StatusCode::kCorrupt,
              "truncated binary PLY: expected 2 face elements, file ends after 1");
}

TEST(PlyErrorTest, AsciiRowWithTooFewValues) {
  ExpectError(ParseString(std::string(kAsciiHeader) + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n"),
              StatusCode::kCorrupt, "line 11: vertex 1: too few values on the line");
  ExpectError(ParseString(std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
              StatusCode::kCorrupt, "line 13: face 0: too few values on the line");
  ExpectError(ParseString(std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n"),
              StatusCode::kCorrupt, "ascii PLY ends early");
  ExpectError(ParseString(std::string(kAsciiHeader) + "0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n"),
              StatusCode::kCorrupt, "line 11: vertex 1: invalid number 'zero'");
}

TEST(PlyErrorTest, IndexOutOfRange) {
  ExpectError(ParseString(std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
              StatusCode::kCorrupt, "face 0 uses vertex index 3 out of range (the file has 3 vertices)");
  ExpectError(ParseString(std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"),
              StatusCode::kCorrupt, "vertex index -1 out of range");
}

TEST(PlyErrorTest, NonFiniteCoordinates) {
  ExpectError(ParseString(std::string(kAsciiHeader) + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
              StatusCode::kCorrupt, "vertex 1 has a NaN or infinite coordinate");
  Bytes body(false);
  body.Put(0.0f).Put(0.0f).Put(0.0f).Put(1.0f).Put(0.0f).Put(0.0f);
  body.Put(0.0f).Put(std::numeric_limits<float>::infinity()).Put(0.0f);
  body.Put<std::uint8_t>(3).Put<std::int32_t>(0).Put<std::int32_t>(1).Put<std::int32_t>(2);
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  ExpectError(ParseString(header + body.str()), StatusCode::kCorrupt,
              "vertex 2 has a NaN or infinite coordinate");
}

TEST(PlyErrorTest, EmptyMeshAndSmallFaces) {
  ExpectError(ParseString("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                          "property float y\nproperty float z\nelement face 0\n"
                          "property list uchar int vertex_indices\nend_header\n"),
              StatusCode::kCorrupt, "PLY has no vertices");
  ExpectError(ParseString("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n1 2 3\n"),
              StatusCode::kCorrupt, "PLY has no faces");
  ExpectError(ParseString(std::string(kAsciiHeader) + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
              StatusCode::kCorrupt, "face 0 has 2 vertex indices; a face needs at least 3");
  ExpectError(ParseString("ply\nformat ascii 1.0\nelement face 0\n"
                          "property list uchar int vertex_indices\nend_header\n"),
              StatusCode::kCorrupt, "no 'vertex' element");
}

TEST(PlyErrorTest, AbsurdCountsFailBeforeAllocating) {
  const std::string binary_header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2147483648\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  ExpectError(ParseString(binary_header + std::string(1000, '\0')), StatusCode::kCorrupt,
              "truncated binary PLY: expected 2147483648 vertex elements, file ends after 83");
  Bytes body(false);
  for (int i = 0; i < 9; ++i) body.Put<float>(static_cast<float>(i));
  body.Put<std::uint8_t>(3).Put<std::int32_t>(0).Put<std::int32_t>(1).Put<std::int32_t>(2);
  const std::string face_header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 4000000000\n"
      "property list uint int vertex_indices\nend_header\n";
  ExpectError(ParseString(face_header + body.str()), StatusCode::kCorrupt,
              "expected 4000000000 face elements");
  // A list whose count claims billions of items.
  Bytes huge_list(false);
  for (int i = 0; i < 9; ++i) huge_list.Put<float>(0.0f);
  huge_list.Put<std::uint32_t>(4000000000u).Put<std::int32_t>(0);
  ExpectError(ParseString(face_header.substr(0, face_header.find("4000000000")) + "1" +
                          face_header.substr(face_header.find("4000000000") + 10) +
                          huge_list.str()),
              StatusCode::kCorrupt, "truncated binary PLY: expected 1 face elements");
  ExpectError(ParseString("ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n0 0 0\n"),
              StatusCode::kCorrupt, "declares 99999999999 vertex rows");
}

TEST(PlyErrorTest, RangeGridProblems) {
  const std::string vertices =
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element range_grid 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n1 1 0\n";
  const std::string size = "obj_info num_cols 2\nobj_info num_rows 2\n";
  ExpectError(ParseString("ply\nformat ascii 1.0\n" + vertices + "1 0\n1 1\n1 2\n1 3\n"),
              StatusCode::kCorrupt, "range_grid element without positive 'obj_info num_cols'");
  ExpectError(ParseString("ply\nformat ascii 1.0\nobj_info num_cols 3\nobj_info num_rows 2\n" +
                          vertices + "1 0\n1 1\n1 2\n1 3\n"),
              StatusCode::kCorrupt, "range_grid has 4 cells but num_cols x num_rows is 3 x 2");
  ExpectError(ParseString("ply\nformat ascii 1.0\n" + size + vertices + "1 0\n2 1 2\n1 2\n1 3\n"),
              StatusCode::kCorrupt, "range_grid cell 1 has 2 vertex indices, expected 0 or 1");
  ExpectError(ParseString("ply\nformat ascii 1.0\n" + size + vertices + "1 0\n1 1\n1 9\n1 3\n"),
              StatusCode::kCorrupt, "range_grid cell 2 uses vertex index 9 out of range");
  ExpectError(ParseString("ply\nformat ascii 1.0\n" + size + vertices + "1 0\n1 1\n0\n1 3\n"),
              StatusCode::kCorrupt, "the range_grid yields no triangles");
}

TEST(PlyErrorTest, BinaryFaceProblems) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  Bytes vertices(false);
  for (int i = 0; i < 9; ++i) vertices.Put<float>(static_cast<float>(i % 4));
  Bytes small = vertices;
  small.Put<std::uint8_t>(2).Put<std::int32_t>(0).Put<std::int32_t>(1);
  ExpectError(ParseString(header + small.str()), StatusCode::kCorrupt,
              "face 0 has 2 vertex indices; a face needs at least 3");
  Bytes out_of_range = vertices;
  out_of_range.Put<std::uint8_t>(3).Put<std::int32_t>(0).Put<std::int32_t>(3).Put<std::int32_t>(1);
  ExpectError(ParseString(header + out_of_range.str()), StatusCode::kCorrupt,
              "face 0 uses vertex index 3 out of range (the file has 3 vertices)");
}

TEST(PlyFileTest, ReadMeshAndWriteMeshUseTheExtension) {
  testing::TempDir dir;
  const TriangleMesh mesh = MakeAwkwardMesh();
  ASSERT_TRUE(WriteMesh(dir.File("a.PLY"), mesh).ok());
  const auto read = ReadMesh(dir.File("a.PLY"));
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ExpectSameMesh(mesh, *read);
  const Status bad = WriteMesh(dir.File("a.stl"), mesh);
  EXPECT_EQ(bad.code(), StatusCode::kUnsupported);
  EXPECT_EQ(bad.message(), dir.File("a.stl") + ": unknown mesh file extension (expected .ply or .obj)");
}

}  // namespace
}  // namespace meshvid
