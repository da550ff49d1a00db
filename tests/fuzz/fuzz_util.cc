#include "tests/fuzz/fuzz_util.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace meshvid::fuzz {

const std::string& ScratchDir() {
  static const std::string dir = [] {
    std::error_code error;
    std::filesystem::path root = std::filesystem::is_directory("/dev/shm", error)
                                     ? std::filesystem::path("/dev/shm")
                                     : std::filesystem::temp_directory_path();
    const std::filesystem::path path =
        root / ("meshvid-fuzz-" + std::to_string(static_cast<long>(::getpid())));
    std::filesystem::create_directories(path, error);
    if (error) Fail("cannot create the scratch folder " + path.string());
    // Removed when the process ends normally (a crash leaves it for inspection).
    static struct Cleanup {
      std::filesystem::path path;
      ~Cleanup() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
      }
    } cleanup{path};
    return path.string();
  }();
  return dir;
}

std::string WriteScratchFile(const std::string& name, std::span<const std::uint8_t> data) {
  const std::string path = ScratchDir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
  if (!out) Fail("cannot write the scratch file " + path);
  return path;
}

}  // namespace meshvid::fuzz
