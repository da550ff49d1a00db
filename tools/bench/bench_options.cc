// Command-line level helpers of meshvid bench (declared in tools/bench/bench_runner.h):
// sequence and list parsing, the shared data folder, timestamps.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <map>
#include <sstream>

#include "tools/bench/bench_runner.h"
#include "tools/sim/ground_truth.h"

namespace meshvid {
namespace {

namespace fs = std::filesystem;

/// Rig rotations that make the frontal arc face the subject (see `meshvid simulate --azimuth`).
const std::map<std::string, double>& KnownAzimuths() {
  static const std::map<std::string, double> table = {{"samba", 90.0}, {"horse-gallop", 90.0}};
  return table;
}

}  // namespace

StatusOr<std::vector<int>> ParseIntList(const std::string& text, int lo, int hi,
                                        const std::string& what) {
  std::vector<int> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(start, end - start);
    char* stop = nullptr;
    const long value = std::strtol(item.c_str(), &stop, 10);
    if (item.empty() || *stop != '\0' || value < lo || value > hi) {
      return InvalidArgumentError(what + " '" + text + "': expected comma-separated integers in " +
                                  std::to_string(lo) + ".." + std::to_string(hi));
    }
    values.push_back(static_cast<int>(value));
    start = end + 1;
  }
  return values;
}

StatusOr<std::vector<BenchSequence>> ResolveBenchSequences(const std::string& list,
                                                           const std::string& shared_data) {
  const std::vector<std::string> scenes = BuiltInSceneNames();
  std::vector<std::string> shared;
  const std::string folder = shared_data.empty() ? "" : shared_data + "/sequences";
  std::error_code error;
  if (!folder.empty() && fs::is_directory(folder, error)) {
    for (const auto& entry : fs::directory_iterator(folder, error)) {
      const fs::path path = entry.path();
      if (path.extension() == ".obj" && fs::exists(fs::path(path).replace_extension(".pc2"))) {
        shared.push_back(path.stem().string());
      }
    }
  }
  std::sort(shared.begin(), shared.end());
  auto make = [](const std::string& name, const std::string& spec) {
    BenchSequence s{name, spec, 0.0};
    const auto it = KnownAzimuths().find(name);
    if (it != KnownAzimuths().end()) s.azimuth_deg = it->second;
    return s;
  };
  std::vector<BenchSequence> sequences;
  if (list.empty()) {
    for (const std::string& name : shared)
      sequences.push_back(make(name, folder + "/" + name + ".obj"));
    for (const std::string& name : scenes) sequences.push_back(make(name, "scene:" + name));
    return sequences;
  }
  std::size_t start = 0;
  while (start <= list.size()) {
    std::size_t end = list.find(',', start);
    if (end == std::string::npos) end = list.size();
    std::string token = list.substr(start, end - start);
    start = end + 1;
    if (token.empty()) continue;
    const std::string scene = token.rfind("scene:", 0) == 0 ? token.substr(6) : token;
    if (std::find(scenes.begin(), scenes.end(), scene) != scenes.end()) {
      sequences.push_back(make(scene, "scene:" + scene));
    } else if (std::find(shared.begin(), shared.end(), token) != shared.end()) {
      sequences.push_back(make(token, folder + "/" + token + ".obj"));
    } else if (token.find_first_of("/.{") != std::string::npos && token.rfind("scene:", 0) != 0) {
      fs::path path(token);
      std::string name =
          path.filename().empty() ? path.parent_path().filename().string() : path.stem().string();
      for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
      }
      sequences.push_back(make(name, token));
    } else {
      std::string known;
      for (const std::string& n : shared) known += (known.empty() ? "" : ", ") + n;
      for (const std::string& n : scenes) known += (known.empty() ? "" : ", ") + n;
      return InvalidArgumentError(
          "unknown sequence '" + token + "': use one of " + known + " or a path to ground truth" +
          (shared.empty() ? " (the shared data folder " + folder + " was not found)"
                          : std::string()));
    }
  }
  if (sequences.empty()) return InvalidArgumentError("--sequences lists no sequence");
  return sequences;
}

StatusOr<std::vector<BenchRig>> ParseRigList(const std::string& text) {
  std::vector<BenchRig> rigs;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(start, end - start);
    start = end + 1;
    const std::size_t dash = item.find('-');
    BenchRig rig;
    char* stop = nullptr;
    const long views = dash == std::string::npos ? 0 : std::strtol(item.c_str(), &stop, 10);
    rig.layout = dash == std::string::npos ? "" : item.substr(dash + 1);
    if (dash == std::string::npos || stop != item.c_str() + dash || views < 1 || views > 64 ||
        (rig.layout != "arc" && rig.layout != "ring")) {
      return InvalidArgumentError("--rigs '" + text +
                                  "': expected comma-separated VIEWS-LAYOUT items such as "
                                  "3-arc,6-ring (1..64 views; layout arc or ring)");
    }
    rig.views = static_cast<int>(views);
    rigs.push_back(rig);
  }
  return rigs;
}

StatusOr<std::vector<std::string>> ParseEncodeArgs(const std::string& text) {
  static const char* const kSetByTheBench[] = {
      "-o", "--out", "--codec", "--quality", "--summary-json", "--frames", "-q", "--quiet"};
  std::vector<std::string> args;
  std::istringstream words(text);
  for (std::string word; words >> word;) args.push_back(word);
  for (const std::string& arg : args) {
    const std::string name = arg.substr(0, arg.find('='));
    for (const char* reserved : kSetByTheBench) {
      if (name == reserved) {
        return InvalidArgumentError("--encode-args '" + text + "': " + name +
                                    " is set by the bench itself for every encode");
      }
    }
  }
  return args;
}

std::string DefaultSharedDataDir() {
  if (const char* env = std::getenv("MESHVID_SHARED_DATA"); env != nullptr && *env != '\0') {
    return env;
  }
  std::error_code error;
  if (fs::is_directory("../shared/data", error)) return "../shared/data";
#ifdef MESHVID_DEFAULT_SHARED_DATA
  if (fs::is_directory(MESHVID_DEFAULT_SHARED_DATA, error)) {
    return fs::path(MESHVID_DEFAULT_SHARED_DATA).lexically_normal().string();
  }
#endif
  return "";
}

std::string UtcTimestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace meshvid
