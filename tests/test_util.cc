#include "tests/test_util.h"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace meshvid::testing {

std::string SharedDataDir() {
  const char* env = std::getenv("MESHVID_SHARED_DATA");
  const std::string dir = env != nullptr ? env : MESHVID_DEFAULT_SHARED_DATA;
  std::error_code ec;
  return std::filesystem::is_directory(dir, ec) ? dir : "";
}

TempDir::TempDir() {
  std::string tmpl = (std::filesystem::temp_directory_path() / "meshvid_test_XXXXXX").string();
  char* made = mkdtemp(tmpl.data());
  if (made == nullptr) ADD_FAILURE() << "cannot create a temporary directory";
  path_ = tmpl;
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

void WriteFile(const std::string& path, const std::string& contents) {
  std::ofstream out(path, std::ios::binary);
  out << contents;
  ASSERT_TRUE(out.good()) << "cannot write " << path;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool HaveMeshvidCli() { return std::getenv("MESHVID_CLI") != nullptr; }

CliRun RunMeshvid(const std::string& arguments, const TempDir& dir) {
  CliRun run;
  const char* cli = std::getenv("MESHVID_CLI");
  if (cli == nullptr) return run;
  const std::string out = dir.File("meshvid_stdout.txt"), err = dir.File("meshvid_stderr.txt");
  const std::string command = std::string("'") + cli + "' " + arguments + " > '" + out +
                              "' 2> '" + err + "' < /dev/null";
  const int status = std::system(command.c_str());
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = ReadFile(out);
  run.err = ReadFile(err);
  return run;
}

std::size_t BoundaryEdgeCount(const TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const Triangle& t : mesh.triangles) {
    for (int c = 0; c < 3; ++c) ++uses[std::minmax(t[c], t[(c + 1) % 3])];
  }
  std::size_t boundary = 0;
  for (const auto& [edge, count] : uses) boundary += count == 1;
  return boundary;
}

TriangleMesh MakeGridPlane(float size, int n, float z) {
  TriangleMesh mesh;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      mesh.positions.emplace_back(size * (static_cast<float>(i) / n - 0.5f),
                                  size * (static_cast<float>(j) / n - 0.5f), z);
      mesh.normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      mesh.triangles.emplace_back(a, b, d);
      mesh.triangles.emplace_back(a, d, c);
    }
  }
  return mesh;
}

ViewCalibration CameraLookingAtOrigin(const Eigen::Vector3f& position, int pixels, double focal) {
  const Eigen::Vector3d forward = -position.cast<double>().normalized();
  const Eigen::Vector3d helper =
      std::abs(forward.y()) < 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d right = forward.cross(helper).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  ViewCalibration camera;
  camera.intrinsics = PinholeIntrinsics{pixels, pixels, focal, focal, (pixels - 1) / 2.0,
                                        (pixels - 1) / 2.0};
  camera.world_from_camera.linear() << right, down, forward;
  camera.world_from_camera.translation() = position.cast<double>();
  camera.has_extrinsics = true;
  return camera;
}

}  // namespace meshvid::testing
