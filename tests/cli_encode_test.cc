// `meshvid encode` end to end on simulated captures, run as the built binary: errors, the
// summary, rate, accuracy and coverage against the ground truth, and the rigid groups the
// arm-block scene's deformation nodes are joined into.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "codec/dec/mvid_decoder.h"
#include "codec/enc/options.h"
#include "format/crc32c.h"
#include "tests/test_util.h"
#include "tools/io/capture.h"
#include "tools/io/mesh_io.h"
#include "tools/sim/ground_truth.h"
#include "tools/sim/scenes.h"

namespace meshvid {
namespace {

/// A file's size and CRC-32C as a machine whose CPU comes from `vendor` writes it.
struct RecordedFile {
  const char* vendor;  ///< /proc/cpuinfo's vendor_id
  std::size_t size;
  std::uint32_t crc;
};

/// The files TheFileIsTheSameWhateverTheMachinesCpu encodes, as two machines write them: an
/// Intel Xeon with AVX-512 FP16 and AMX, and an AMD EPYC. Each writes the same file with libm
/// told the CPU lacks AVX (below) and with libaom held to no SIMD (AOM_SIMD_CAPS_MASK=0), so
/// neither library is what differs between them. A change of the encoder that changes its
/// files on purpose records the new file of the machine at hand and removes the other
/// vendor's entry; a machine of a vendor without an entry skips the comparison, printing
/// what to record.
constexpr RecordedFile kRecordedFiles[] = {{"GenuineIntel", 17263, 0x8ad6d91a},
                                           {"AuthenticAMD", 17315, 0x46262709}};

/// This machine's CPU vendor as /proc/cpuinfo's vendor_id states it; "" if it does not.
std::string CpuVendor() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("vendor_id", 0) != 0) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) return "";
    const std::size_t start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? "" : line.substr(start);
  }
  return "";
}

/// Simulates the arm-block at 160 x 120 pixels (`frames` frames, `views` views) into
/// `dir`/cap (with `simulate_options` added to the simulate command) and encodes it at the
/// defaults into `dir`/`file`; returns the encode's command line up to its output file, for
/// encoding the capture again (empty after a failure).
std::string SimulateAndEncodeSmallArmBlock(const testing::TempDir& dir, int frames, int views,
                                           const std::string& file,
                                           const std::string& simulate_options = "") {
  testing::CliRun run = testing::RunMeshvid(
      "simulate scene:arm-block -o '" + dir.File("cap") + "' --frames 0:" + std::to_string(frames) +
          " --views " + std::to_string(views) + " --res 160x120 -q " + simulate_options,
      dir);
  if (run.exit_code != 0) {
    ADD_FAILURE() << "simulate: " << run.err;
    return {};
  }
  const std::string encode = "encode '" + dir.File("cap/manifest.json") + "' -q -o ";
  run = testing::RunMeshvid(encode + "'" + dir.File(file) + "'", dir);
  if (run.exit_code != 0) {
    ADD_FAILURE() << "encode: " << run.err;
    return {};
  }
  return encode;
}

TEST(EncodeCliTest, HelpListsTheUsersOptionsAndTuneHelpEveryKnob) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  testing::CliRun run = testing::RunMeshvid("encode --help", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // One line per option starts with two spaces and a dash; the internals are behind --tune.
  int options = 0;
  for (std::size_t at = 0; (at = run.out.find("\n  -", at)) != std::string::npos; ++at) ++options;
  EXPECT_LE(options, 20) << run.out;
  EXPECT_NE(run.out.find("--tune"), std::string::npos);
  EXPECT_EQ(run.out.find("--node-spacing"), std::string::npos);
  // `--tune help` needs no capture: it lists every key with its default and range.
  run = testing::RunMeshvid("encode --tune help", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const TuningKnob& knob : TuningKnobs()) {
    EXPECT_NE(run.out.find(std::string("  ") + knob.key + " = "), std::string::npos) << knob.key;
  }
  EXPECT_NE(run.out.find("node_spacing = 0  (double, >= 0)"), std::string::npos) << run.out;
}

// The same capture encodes to the same bytes on every machine (for the same thread count):
// Embree is held to one instruction set (embree_scene.cc), and the C library's maths, which
// picks its kernels by the CPU's features too, leaves the file unchanged when told the CPU
// has no AVX or FMA, as on an older machine. The bytes are also those recorded on the machine
// that wrote this test, so a run on another machine compares two machines.
TEST(EncodeCliTest, TheFileIsTheSameWhateverTheMachinesCpu) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string encode = SimulateAndEncodeSmallArmBlock(dir, 3, 3, "here.mvid");
  ASSERT_FALSE(encode.empty());
  const char* previous = std::getenv("GLIBC_TUNABLES");
  const std::string kept = previous != nullptr ? previous : "";
  setenv("GLIBC_TUNABLES", "glibc.cpu.hwcaps=-AVX2,-FMA,-AVX,-FMA4,-AVX512F", 1);
  const testing::CliRun run =
      testing::RunMeshvid(encode + "'" + dir.File("older-cpu.mvid") + "'", dir);
  if (previous != nullptr) {
    setenv("GLIBC_TUNABLES", kept.c_str(), 1);
  } else {
    unsetenv("GLIBC_TUNABLES");
  }
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(testing::ReadFile(dir.File("here.mvid")),
            testing::ReadFile(dir.File("older-cpu.mvid")));
  // The recorded bytes are the geometry's (--no-colour): both machines' files were recorded
  // before the colour stream existed, and the geometry of a file is the same with colour.
  const testing::CliRun grey =
      testing::RunMeshvid(encode + "'" + dir.File("grey.mvid") + "' --no-colour", dir);
  ASSERT_EQ(grey.exit_code, 0) << grey.err;
  const std::string here = testing::ReadFile(dir.File("grey.mvid"));
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(here.data());
  const std::uint32_t crc = Crc32c({bytes, here.size()});
  const std::string vendor = CpuVendor();
  const auto recorded =
      std::find_if(std::begin(kRecordedFiles), std::end(kRecordedFiles),
                   [&](const RecordedFile& file) { return vendor == file.vendor; });
  if (recorded == std::end(kRecordedFiles)) {
    GTEST_SKIP() << "no file recorded for a CPU of vendor '" << vendor << "'; this machine writes "
                 << here.size() << " bytes, CRC-32C 0x" << std::hex << crc
                 << ": record them in kRecordedFiles";
  }
  EXPECT_TRUE(recorded->size == here.size() && recorded->crc == crc)
      << "a changed encoder, or a machine of this vendor that writes other bytes: "
      << here.size() << " bytes, CRC-32C 0x" << std::hex << crc << " (recorded: "
      << std::dec << recorded->size << " bytes, 0x" << std::hex << recorded->crc << ")";
}

// Colour in the views (here PLY red green blue) is read with the capture and does not move
// the geometry: the file is the one the same capture without colour gives.
TEST(EncodeCliTest, ColoursInTheViewsLeaveTheFileAsItWas) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string encode = SimulateAndEncodeSmallArmBlock(dir, 2, 2, "plain.mvid", "--no-colour");
  ASSERT_FALSE(encode.empty());
  auto capture = CaptureSequence::Open(dir.File("cap/manifest.json"));
  ASSERT_TRUE(capture.ok()) << capture.status().ToString();
  for (int frame = 0; frame < (*capture)->frame_count(); ++frame) {
    for (int view = 0; view < (*capture)->view_count(); ++view) {
      const std::string& path = (*capture)->view_path(frame, view);
      auto mesh = ReadMesh(path);
      ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
      for (std::size_t v = 0; v < mesh->vertex_count(); ++v) {
        mesh->colours.emplace_back(v % 256, (v / 256) % 256, 40 * view);
      }
      ASSERT_TRUE(WriteMesh(path, *mesh).ok());
    }
  }
  const auto coloured = (*capture)->LoadView(1, 1);
  ASSERT_TRUE(coloured.ok()) << coloured.status().ToString();
  ASSERT_EQ(coloured->colours.size(), coloured->vertex_count());
  EXPECT_EQ(coloured->colours[300], Colour(300 % 256, 1, 40));
  std::string geometry_only = encode;
  geometry_only.insert(geometry_only.rfind("-o "), "--no-colour ");
  const testing::CliRun run =
      testing::RunMeshvid(geometry_only + "'" + dir.File("coloured.mvid") + "'", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(testing::ReadFile(dir.File("plain.mvid")),
            testing::ReadFile(dir.File("coloured.mvid")));
}

TEST(EncodeCliTest, ExplainsBadInputAndLeavesNoFileBehind) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string out = dir.File("out.mvid");
  testing::CliRun run = testing::RunMeshvid("encode '" + dir.File("nope.json") + "' -o '" + out + "'", dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("nope.json"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(out + ".partial"));

  run = testing::RunMeshvid("simulate scene:arm-block -o '" + dir.File("cap") + "' --frames 0:2 -q", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                "' --quality 120 -q",
                            dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--quality"), std::string::npos) << run.err;
  // The library names EncoderTuning's fields (tuning.proxy_fraction); the command, --tune KEY.
  run = testing::RunMeshvid(
      "encode '" + dir.File("cap/manifest.json") + "' -o '" + out + "' --tune proxy_fraction=2 -q",
      dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--tune proxy_fraction must be in [0.001, 1]"), std::string::npos)
      << run.err;
  EXPECT_EQ(run.err.find("tuning.proxy_fraction"), std::string::npos) << run.err;
  run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                "' --tune base_voxel_scale=0 -q",
                            dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--tune base_voxel_scale must be in [0.25, 8]"), std::string::npos)
      << run.err;
  run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                "' --tune deform_rigid_group_factor=-1 -q",
                            dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--tune deform_rigid_group_factor must be >= 0"), std::string::npos)
      << run.err;
  run = testing::RunMeshvid(
      "encode '" + dir.File("cap/manifest.json") + "' -o '" + out + "' --tune rigid_groups=1 -q",
      dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("unknown tuning key 'rigid_groups'"), std::string::npos) << run.err;
  // Every --tune counts, not only the first or the last one.
  run =
      testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                              "' --tune node_spacing=0.05 --tune rigid_groups=1 --tune window=4 -q",
                          dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("unknown tuning key 'rigid_groups'"), std::string::npos) << run.err;
  // A JSON file of knobs is read as KEY=VALUE entries are, and checked the same.
  testing::WriteFile(dir.File("tune.json"), R"({"node_spacing": 0.05, "window": 1})");
  run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                "' --tune '" + dir.File("tune.json") + "' -q",
                            dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--tune window must be >= 2"), std::string::npos) << run.err;
  // A flag that became a --tune key is named with its key.
  run = testing::RunMeshvid(
      "encode '" + dir.File("cap/manifest.json") + "' -o '" + out + "' --rigid-groups 1 -q", dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--rigid-groups is now --tune deform_rigid_group_factor=VALUE"),
            std::string::npos)
      << run.err;
  run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                "' --codec mpeg2 -q",
                            dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("mpeg2"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // By default the whole base surface is decoded; --hide-unseen writes the mask of base
  // triangles no view saw.
  for (const char* flag : {"", " --hide-unseen"}) {
    run = testing::RunMeshvid("encode '" + dir.File("cap/manifest.json") + "' -o '" + out +
                                  "' -q" + flag,
                              dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    auto decoder = MvidDecoder::OpenFile(out);
    ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
    const auto& mask = (*decoder)->motion().surface_triangles;
    if (*flag == '\0') {
      EXPECT_TRUE(mask.empty());
    } else {
      ASSERT_EQ(mask.size(), (*decoder)->base_mesh().triangle_count());
      EXPECT_GT(std::count(mask.begin(), mask.end(), 0), 0) << "the back was never seen";
      EXPECT_GT(std::count(mask.begin(), mask.end(), 1), 0);
    }
  }
  std::filesystem::remove(out);
  run = testing::RunMeshvid("encode --help", dir);
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("--rebase-gain"), std::string::npos);
  // The piecewise-rigid segmentation the deformation replaced is gone, flags and all.
  EXPECT_EQ(run.out.find("--deform "), std::string::npos);
  run = testing::RunMeshvid(
      "encode '" + dir.File("cap/manifest.json") + "' -o '" + out + "' --deform 0 -q", dir);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("--deform"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

/// The arm-block scene, simulated and encoded by tests/make_arm_block_inputs.sh. Under ctest the
/// script runs once per run, before these tests, and MESHVID_TEST_ARM_BLOCK_INPUTS names its
/// folder; a test process run alone runs the script into its own folder. The capture, the file,
/// its summary and what the encode printed are read through Shared(); each test's own files go
/// in dir_.
class ArmBlockEncode : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!testing::HaveMeshvidCli()) return;
    dir_ = new testing::TempDir;
    const char* made = std::getenv("MESHVID_TEST_ARM_BLOCK_INPUTS");
    if (made != nullptr && *made != '\0') {
      shared_ = made;
      return;
    }
    shared_ = dir_->File("shared");
    const std::string command = std::string("bash '") + MESHVID_MAKE_ARM_BLOCK_INPUTS + "' '" +
                                std::getenv("MESHVID_CLI") + "' '" + shared_ + "' " +
                                std::to_string(kFrames) + " 2> '" + dir_->File("make.txt") + "'";
    if (std::system(command.c_str()) != 0) make_error_ = testing::ReadFile(dir_->File("make.txt"));
  }
  static void TearDownTestSuite() { delete dir_; }
  void SetUp() override {
    MESHVID_REQUIRE_CLI();
    ASSERT_TRUE(make_error_.empty()) << "making the arm-block inputs failed: " << make_error_;
    ASSERT_TRUE(std::filesystem::exists(Shared("summary.json")))
        << "no arm-block encode in " << shared_;
    encode_err_ = testing::ReadFile(Shared("encode-stderr.txt"));
  }
  /// A file of the shared capture and encode.
  static std::string Shared(const std::string& name) { return shared_ + "/" + name; }
  /// The frames simulated; CMakeLists.txt passes the same count to the script.
  static constexpr int kFrames = 16;
  static testing::TempDir* dir_;
  static std::string shared_;
  static std::string make_error_;
  std::string encode_err_;
};
testing::TempDir* ArmBlockEncode::dir_ = nullptr;
std::string ArmBlockEncode::shared_;
std::string ArmBlockEncode::make_error_;

TEST_F(ArmBlockEncode, SummaryStatesTheStreamsAndRate) {
  EXPECT_NE(encode_err_.find("segments"), std::string::npos) << encode_err_;
  EXPECT_NE(encode_err_.find("Mbit/s"), std::string::npos) << encode_err_;
  const nlohmann::json s = nlohmann::json::parse(testing::ReadFile(Shared("summary.json")));
  EXPECT_EQ(s["frames"], kFrames);
  EXPECT_EQ(s["views"], 3);
  EXPECT_GE(s["segments"].get<int>(), 2);
  const auto total = s["bytes_total"].get<std::uint64_t>();
  EXPECT_EQ(total, std::filesystem::file_size(Shared("arm.mvid")));
  EXPECT_GE(total, s["bytes_base"].get<std::uint64_t>() + s["bytes_motion"].get<std::uint64_t>() +
                       s["bytes_transforms"].get<std::uint64_t>() +
                       s["bytes_video"].get<std::uint64_t>());
  EXPECT_LT(s["bytes_video"].get<std::uint64_t>(), total);
  EXPECT_GT(s["filled_share"].get<double>(), 0.0);
  EXPECT_LT(s["filled_share"].get<double>(), 1.0);
}

TEST_F(ArmBlockEncode, DecodedSequenceCoversAtLeastTheInputAndStaysNearTheTruth) {
  const std::string gt = Shared("cap/ground_truth.obj");
  testing::CliRun run =
      testing::RunMeshvid("eval --ref '" + gt + "' --test '" + Shared("arm.mvid") +
                              "' --samples 40000 -q --json '" + dir_->File("mvid.json") + "'",
                          *dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = testing::RunMeshvid("eval --ref '" + gt + "' --test '" + Shared("cap/manifest.json") +
                                "' --samples 40000 -q --json '" + dir_->File("raw.json") + "'",
                            *dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto mvid = nlohmann::json::parse(testing::ReadFile(dir_->File("mvid.json")))["mean"];
  const auto raw = nlohmann::json::parse(testing::ReadFile(dir_->File("raw.json")))["mean"];
  EXPECT_GE(mvid["coverage"].get<double>(), raw["coverage"].get<double>()) << mvid << raw;
  // A regression guard at the measured level (about 30 mm RMS on these 16 frames: the
  // tracking of the fast arm lags; issue 4's goal, under the 1 mm sensor noise, is not met).
  EXPECT_LT(mvid["accuracy_rms"].get<double>(), 0.05) << mvid;
}

/// Per part of the arm-block scene (`parts`, per ground-truth vertex), the share of the base
/// vertices of the key group of `mvid` holding `frame` near that part whose strongest segment
/// lies in the part's most common rigid group: segments whose decoded transforms are equal in
/// every frame of the key group (one segment each, unless the encoder joined nodes into rigid
/// groups). The key group must hold at least 3 frames for its grouping to say anything.
std::map<std::string, double> PartSharesInOneGroup(const std::string& mvid,
                                                   const std::vector<std::string>& parts,
                                                   std::uint32_t frame) {
  std::map<std::string, double> shares;
  auto decoder = MvidDecoder::OpenFile(mvid);
  EXPECT_TRUE(decoder.ok()) << decoder.status().ToString();
  if (!decoder.ok()) return shares;
  MvidKeyGroupSpan group;
  for (const MvidKeyGroupSpan& span : (*decoder)->info().key_groups) {
    if (span.first_frame <= frame && frame < span.first_frame + span.frame_count) group = span;
  }
  EXPECT_GE(group.frame_count, 3u) << "the key group holding frame " << frame;
  auto truth = OpenGroundTruth("scene:arm-block");
  EXPECT_TRUE(truth.ok());
  if (!truth.ok()) return shares;
  auto key_frame = (*truth)->Frame(group.first_frame);
  EXPECT_TRUE(key_frame.ok());
  if (!key_frame.ok()) return shares;
  // Each segment's transforms through the key group, as a key for grouping.
  std::vector<std::vector<float>> tracks;
  for (std::uint32_t f = 0; f < group.frame_count; ++f) {
    auto transforms = (*decoder)->DecodeTransforms(group.first_frame + f);
    EXPECT_TRUE(transforms.ok());
    if (!transforms.ok()) return shares;
    tracks.resize(transforms->size());
    for (std::size_t s = 0; s < tracks.size(); ++s) {
      const RigidTransform& t = (*transforms)[s];
      tracks[s].insert(tracks[s].end(), {t.rotation.w(), t.rotation.x(), t.rotation.y(),
                                         t.rotation.z(), t.translation.x(), t.translation.y(),
                                         t.translation.z()});
    }
  }
  const MotionModel& motion = (*decoder)->motion();
  std::map<std::vector<float>, int> group_ids;
  std::vector<int> group_of_segment(tracks.size());
  for (std::size_t s = 0; s < tracks.size(); ++s) {
    group_of_segment[s] = group_ids.try_emplace(tracks[s], int(group_ids.size())).first->second;
  }
  // Each base vertex takes the part of the nearest ground-truth vertex and votes for the group
  // of its strongest segment.
  const TriangleMesh& base = (*decoder)->base_mesh();
  std::map<std::string, std::map<int, int>> votes;
  std::map<std::string, int> totals;
  for (std::size_t v = 0; v < base.vertex_count(); ++v) {
    std::size_t nearest = 0;
    float best = 1e30f;
    for (std::size_t g = 0; g < key_frame->vertex_count(); ++g) {
      const float d = (key_frame->positions[g] - base.positions[v]).squaredNorm();
      if (d < best) best = d, nearest = g;
    }
    if (best > 0.01f * 0.01f) continue;  // base vertices away from the object (fused hull)
    const VertexBlend& blend = motion.blends[v];
    const auto strongest = std::max_element(
        blend.influences.begin(), blend.influences.begin() + blend.count,
        [](const BlendInfluence& a, const BlendInfluence& b) { return a.weight < b.weight; });
    ++votes[parts[nearest]][group_of_segment[strongest->segment]];
    ++totals[parts[nearest]];
  }
  EXPECT_GT(totals["block"], 50);
  for (const auto& [part, part_votes] : votes) {
    int top = 0;
    for (const auto& [id, count] : part_votes) top = std::max(top, count);
    shares[part] = double(top) / totals[part];
    std::printf("%s: %.1f%% of %d base vertices in one group (%zu groups of %zu segments; key "
                "group of %u frames)\n",
                part.c_str(), 100 * shares[part], totals[part], group_ids.size(), tracks.size(),
                group.frame_count);
  }
  return shares;
}

// Frames 0-5, where the hand moves 40-50 mm a frame, held to one key group. The fused base
// leaves the hand's shell apart from the block it holds: held to the nearest nodes of the
// block and the forearm it follows them, and under 2% of the frames' points lie beyond the
// displacements' reach; left free (deform_join_pieces=0) it drifts onto the block's data and
// about 8% do.
TEST_F(ArmBlockEncode, TheHandsSeparateShellMovesWithWhatItTouches) {
  auto worst_unexplained = [&](const std::string& join) {
    const std::string json = dir_->File("join-" + join + ".json");
    const testing::CliRun run = testing::RunMeshvid(
        "encode '" + Shared("cap/manifest.json") + "' -o '" + dir_->File("join.mvid") +
            "' --frames 0:6 --max-key-groups 1 --tune deform_join_pieces=" + join +
            " -q --summary-json '" + json + "'",
        *dir_);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    if (run.exit_code != 0) return -1.0;
    const nlohmann::json summary = nlohmann::json::parse(testing::ReadFile(json));
    EXPECT_EQ(summary["key_groups"].size(), 1u);
    return summary["key_groups"][0]["worst_unexplained"].get<double>();
  };
  const double joined = worst_unexplained("1.5");
  const double apart = worst_unexplained("0");
  EXPECT_GE(joined, 0.0);
  EXPECT_LT(joined, 0.02);
  EXPECT_GT(apart, 0.04);
}

TEST_F(ArmBlockEncode, TheBlockAndTheArmEachMoveAsOneRigidGroup) {
  const std::string mvid = dir_->File("arm-deform.mvid");
  const testing::CliRun enc = testing::RunMeshvid(
      "encode '" + Shared("cap/manifest.json") + "' -o '" + mvid +
          "' --tune deform_rigid_group_factor=1 --rebase-gain 4 --summary-json '" +
          dir_->File("deform.json") + "'",
      *dir_);
  ASSERT_EQ(enc.exit_code, 0) << enc.err;
  EXPECT_EQ(enc.err.find("warning"), std::string::npos) << enc.err;
  // The summary speaks of the deformation's nodes and groups.
  EXPECT_NE(enc.err.find("(deformation nodes) moving as"), std::string::npos) << enc.err;
  const nlohmann::json summary =
      nlohmann::json::parse(testing::ReadFile(dir_->File("deform.json")));
  for (const auto& group : summary["key_groups"]) {
    EXPECT_GE(group["rigid_groups"].get<int>(), 1);
    EXPECT_LT(group["rigid_groups"].get<int>(), group["segments"].get<int>());
    // The figures of the rule that ended the key group, all -1 where the capture ended it.
    const bool ended_by_capture = group["cut_unexplained"].get<double>() == -1;
    EXPECT_EQ(group["cut_seen_through"].get<double>() == -1, ended_by_capture);
    EXPECT_EQ(group["cut_farthest_growth"].get<double>() == -1, ended_by_capture);
    EXPECT_EQ(group["cut_loss_db"].get<double>() == -1, ended_by_capture);
    // Tracked forwards only (deform_backward_frames 0): every key group starts at its key frame.
    EXPECT_EQ(group["key_frame"].get<int>(), group["first_frame"].get<int>());
  }
  EXPECT_EQ(summary["key_groups"].back()["cut_farthest_growth"].get<double>(), -1);
  // The groups are judged over the frames of the key group holding frame 10, where the arm
  // slows (its hand moves 8-20 mm a frame at frames 9-12, against 40-50 mm at frames 0-6);
  // --rebase-gain 4 lets a key group hold several frames there. The arm bends at the elbow
  // and turns at the wrist: its rigid pieces are the upper arm, the forearm and the hand.
  // Through fast frames a piece's tracked nodes stray from one rigid motion by more than the
  // grouping's tolerance in some frame, and how far they stray turns on rounding (a change of
  // Embree's instruction set moves the block's share by several points, and so does the
  // machine: 78% on a machine that wrote another file than kRecordedFiles' first, 89.7% of the
  // upper arm on the AMD EPYC of the second): the test asks 85% of the upper arm and of the
  // forearm in one group, and three quarters of the block and of the hand (the smallest
  // piece). The shares of the recorded run are in bench/ENCODE.md.
  std::map<std::string, double> shares = PartSharesInOneGroup(mvid, ArmBlockVertexPieces(), 10);
  std::string all;
  for (const auto& [piece, share] : shares) all += piece + " " + std::to_string(share) + "; ";
  EXPECT_GE(shares["block"], 0.75) << all;
  EXPECT_GE(shares["upper_arm"], 0.85) << all;
  EXPECT_GE(shares["forearm"], 0.85) << all;
  EXPECT_GE(shares["hand"], 0.75) << all;
  // The whole arm bends at the elbow, so less of it moves as one.
  shares = PartSharesInOneGroup(mvid, ArmBlockVertexParts(), 10);
  EXPECT_GE(shares["arm"], 0.4);
}

}  // namespace
}  // namespace meshvid
