// Helpers shared by the unit tests: temporary directories and the location of shared data.
#ifndef MESHVID_TESTS_TEST_UTIL_H_
#define MESHVID_TESTS_TEST_UTIL_H_

#include <string>

#include "codec/common/camera.h"
#include "codec/common/mesh.h"

namespace meshvid::testing {

/// The project's shared data folder (`../shared/data` beside the checkout, or the
/// MESHVID_SHARED_DATA environment variable), or "" if it is absent.
std::string SharedDataDir();

/// A fresh empty directory, removed when the object is destroyed.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  /// path() + "/" + name.
  std::string File(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

/// Writes `contents` to `path` (binary), failing the test on error.
void WriteFile(const std::string& path, const std::string& contents);
/// Reads a whole file into a string.
std::string ReadFile(const std::string& path);

/// What a run of the built `meshvid` executable printed and returned.
struct CliRun {
  int exit_code = -1;  ///< -1 if it did not exit normally
  std::string out;     ///< standard output
  std::string err;     ///< standard error
};

/// True if the path of the built `meshvid` is known (MESHVID_CLI, set by CTest).
bool HaveMeshvidCli();
/// Runs `meshvid ARGUMENTS` (a shell command line tail; quote paths), capturing its output
/// in files of `dir`.
CliRun RunMeshvid(const std::string& arguments, const TempDir& dir);

/// A flat square grid mesh in the z = `z` plane, side `size`, `n` x `n` quads, centred on the
/// origin, normals along +z.
TriangleMesh MakeGridPlane(float size, int n, float z = 0.0f);

/// A calibrated pinhole camera at `position` looking at the origin: a square image of
/// `pixels`, focal length `focal` in pixels, principal point in the middle.
ViewCalibration CameraLookingAtOrigin(const Eigen::Vector3f& position, int pixels, double focal);

/// Edges used by one triangle only: the length of the surface's boundary, in edges.
std::size_t BoundaryEdgeCount(const TriangleMesh& mesh);

}  // namespace meshvid::testing

/// Skips the current test with a message when the shared data folder is absent; otherwise
/// declares `const std::string shared_data` holding its path.
#define MESHVID_REQUIRE_SHARED_DATA()                                                \
  const std::string shared_data = ::meshvid::testing::SharedDataDir();               \
  if (shared_data.empty()) GTEST_SKIP() << "shared data (../shared/data) is absent; " \
                                           "set MESHVID_SHARED_DATA to run this test"

/// Skips the current test when the built `meshvid` is unknown (run outside CTest).
#define MESHVID_REQUIRE_CLI()                         \
  if (!::meshvid::testing::HaveMeshvidCli())          \
  GTEST_SKIP() << "MESHVID_CLI is not set; run this test through ctest"

#endif  // MESHVID_TESTS_TEST_UTIL_H_
