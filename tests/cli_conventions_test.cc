// The conventions every `meshvid` command follows, run as the built binary: frame ranges past
// the end, partial files, per-key-group sizes, repeated errors, grammar, --json FILE|-,
// summaries on stderr, progress in logs, --normals, where the simulated cameras look, and what
// an encode held to too few key groups says.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "codec/dec/mvid_decoder.h"
#include "tests/mvid_mutants.h"
#include "tests/test_util.h"
#include "tools/io/mesh_io.h"

namespace meshvid {
namespace {

/// 12 frames in key groups 0-4, 5-8, 9-11 whose finest levels differ (258, 1026, 258 vertices).
const std::string kThreeKeyGroups = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v2.mvid";

std::size_t Occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++count;
  }
  return count;
}

/// kThreeKeyGroups promising its 12 frames in its header, cut before the group of frames 8..9
/// (8 frames readable), written to `path`.
void WritePartialFile(const std::string& path) {
  const std::string golden = testing::ReadFile(kThreeKeyGroups);
  const std::vector<std::uint8_t> promising =
      testing::WithHeaderFrameCount(std::vector<std::uint8_t>(golden.begin(), golden.end()), 12);
  testing::WriteFile(path, std::string(promising.begin(), promising.begin() + 10750));
}

/// Simulates `frames` frames of the arm-block scene into dir/cap at a small resolution.
void SimulateArmBlock(const testing::TempDir& dir, int frames) {
  const testing::CliRun run =
      testing::RunMeshvid("simulate scene:arm-block -o '" + dir.File("cap") +
                              "' --frames 0:" + std::to_string(frames) + " --res 320x240 -q",
                          dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
}

TEST(CliConventionsTest, AFrameRangePastTheEndIsClippedWithAWarningByEveryCommand) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string warning =
      "meshvid: warning: --frames: frame range '10:20' runs past the last of the 12 frames: "
      "using 10:12";
  const testing::CliRun decode = testing::RunMeshvid(
      "decode '" + kThreeKeyGroups + "' --no-write --frames 10:20 --json -", dir);
  ASSERT_EQ(decode.exit_code, 0) << decode.err;
  EXPECT_NE(decode.err.find(warning), std::string::npos) << decode.err;
  EXPECT_EQ(nlohmann::json::parse(decode.out)["frames"], 2);
  const testing::CliRun exported = testing::RunMeshvid(
      "export '" + kThreeKeyGroups + "' -o '" + dir.File("e.obj") + "' --frames 10:20 -q", dir);
  EXPECT_EQ(exported.exit_code, 0) << exported.err;
  EXPECT_NE(exported.err.find(warning), std::string::npos) << exported.err;
  const testing::CliRun rendered =
      testing::RunMeshvid("render '" + kThreeKeyGroups + "' -o '" + dir.File("r{frame}.png") +
                              "' --frames 10:20 --size 32x32 -q",
                          dir);
  EXPECT_EQ(rendered.exit_code, 0) << rendered.err;
  EXPECT_NE(rendered.err.find("run past the 12 frames every input has: drawing 10:12"),
            std::string::npos)
      << rendered.err;
  EXPECT_TRUE(std::filesystem::exists(dir.File("r11.png")));
  // A range with no frame left is an error, the same in every command.
  for (const std::string& command :
       {"decode '" + kThreeKeyGroups + "' --no-write",
        "export '" + kThreeKeyGroups + "' -o '" + dir.File("f.obj") + "'"}) {
    const testing::CliRun none = testing::RunMeshvid(command + " --frames 20:30", dir);
    EXPECT_EQ(none.exit_code, 1) << command;
    EXPECT_NE(none.err.find("--frames: frame range '20:30' selects no frame of the 12 frames"),
              std::string::npos)
        << none.err;
  }
}

TEST(CliConventionsTest, APartialFileIsRefusedUnlessAllowedAndNamedByEveryCommand) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string cut = dir.File("cut.mvid");
  WritePartialFile(cut);
  const std::string refused =
      "partial file: only 8 of the 12 frames its header promises are "
      "readable";
  const std::string warned = "meshvid: warning: " + cut +
                             ": partial file: only 8 of the 12 frames its header promises "
                             "are readable; reading frames 0..7";
  // Decode the whole file once as the reference eval compares with.
  ASSERT_EQ(testing::RunMeshvid(
                "decode '" + kThreeKeyGroups + "' -q -o '" + dir.File("g{frame}.obj") + "'", dir)
                .exit_code,
            0);
  const std::vector<std::string> commands = {
      "decode '" + cut + "' --no-write -q",
      "export '" + cut + "' -o '" + dir.File("e.glb") + "' -q",
      "render '" + cut + "' -o '" + dir.File("r.png") + "' --size 32x32 -q",
      "eval --ref '" + dir.File("g{frame}.obj") + "' --test '" + cut +
          "' --ref-first 0 --samples 1000 -q"};
  for (const std::string& command : commands) {
    const testing::CliRun strict = testing::RunMeshvid(command, dir);
    EXPECT_EQ(strict.exit_code, 1) << command << "\n" << strict.err;
    EXPECT_NE(strict.err.find(refused), std::string::npos) << command << "\n" << strict.err;
    EXPECT_NE(strict.err.find("--allow-partial"), std::string::npos) << strict.err;
    const testing::CliRun allowed = testing::RunMeshvid(command + " --allow-partial", dir);
    EXPECT_EQ(allowed.exit_code, 0) << command << "\n" << allowed.err;
    EXPECT_NE(allowed.err.find(warned), std::string::npos) << command << "\n" << allowed.err;
  }
  // info describes it (exit 0) and says it is partial; --check fails on it.
  const testing::CliRun info = testing::RunMeshvid("info '" + cut + "' --json -", dir);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.err.find(warned.substr(0, warned.find(';'))), std::string::npos) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["frames"], 8);
  EXPECT_EQ(j["declared_frames"], 12);
  EXPECT_EQ(j["partial"], true);
  const testing::CliRun check = testing::RunMeshvid("info '" + cut + "' --check", dir);
  EXPECT_EQ(check.exit_code, 1);
  // The problem is listed once (in the report), stderr says only that the check failed.
  EXPECT_EQ(Occurrences(check.out + check.err, "no TRLR chunk"), 1u) << check.out << check.err;
  EXPECT_NE(check.err.find("meshvid: " + cut + ": the check failed (1 problem, listed above)"),
            std::string::npos)
      << check.err;
}

TEST(CliConventionsTest, DecodeReportsTheSizeOfEveryKeyGroup) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const testing::CliRun run =
      testing::RunMeshvid("decode '" + kThreeKeyGroups + "' --no-write --json -", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  StatusOr<std::unique_ptr<MvidDecoder>> decoder = MvidDecoder::OpenFile(kThreeKeyGroups);
  ASSERT_TRUE(decoder.ok());
  ASSERT_EQ(j["key_groups"].size(), 3u);
  double vertex_frames = 0;
  for (const nlohmann::json& group : j["key_groups"]) {
    const auto mesh = (*decoder)->DecodeFrame(group["first_frame"].get<std::uint32_t>(), 2);
    ASSERT_TRUE(mesh.ok());
    EXPECT_EQ(group["vertices"], mesh->vertex_count());
    EXPECT_EQ(group["triangles"], mesh->triangle_count());
    vertex_frames += double(mesh->vertex_count()) * group["frames"].get<int>();
  }
  EXPECT_EQ(j["key_groups"][1]["first_frame"], 5);
  EXPECT_EQ(j["vertices_min"], 258);
  EXPECT_EQ(j["vertices_max"], 1026);
  EXPECT_DOUBLE_EQ(j["vertices"].get<double>(), vertex_frames / 12);
  EXPECT_NE(run.err.find("258..1026 vertices, 512..2048 triangles, the same within each of 3 "
                         "key groups"),
            std::string::npos)
      << run.err;
  const testing::CliRun help = testing::RunMeshvid("decode --help", dir);
  EXPECT_EQ(help.out.find("Every frame of a level has the same triangles"), std::string::npos);
  EXPECT_NE(help.out.find("every frame of a key group has the same triangles"), std::string::npos);
}

TEST(CliConventionsTest, AnOutputThatCannotBeWrittenIsNamedOnce) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  for (const std::string output : {"/proc/meshvid-r.png", "/proc/meshvid-e.glb"}) {
    const std::string command = output.ends_with(".png") ? "render" : "export";
    const testing::CliRun run =
        testing::RunMeshvid(command + " '" + kThreeKeyGroups + "' -o " + output + " -q", dir);
    EXPECT_EQ(run.exit_code, 1) << run.err;
    EXPECT_EQ(Occurrences(run.err, output), 1u) << run.err;
    EXPECT_EQ(run.err.find(kThreeKeyGroups), std::string::npos) << run.err;
  }
}

TEST(CliConventionsTest, CountsAgreeInNumber) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  const std::string one_group = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v1.mvid";
  const testing::CliRun info = testing::RunMeshvid("info '" + one_group + "'", dir);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("6 frames at 25 fps (0.24 s) in 2 groups of up to 4 frames"),
            std::string::npos)
      << info.out;
  const std::regex singular_noun_after_plural_count(
      "\\b1 (groups|key groups|frames|segments|rigid pieces|views)\\b");
  EXPECT_FALSE(std::regex_search(info.out, singular_noun_after_plural_count)) << info.out;

  SimulateArmBlock(dir, 1);
  const testing::CliRun one = testing::RunMeshvid(
      "encode '" + dir.File("cap") + "' -o '" + dir.File("one.mvid") + "'", dir);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.err.find("Encoded 1 frame x 3 views of"), std::string::npos) << one.err;
  EXPECT_FALSE(std::regex_search(one.err, singular_noun_after_plural_count)) << one.err;
  // The encode summary counts key group 0's segments as info does.
  std::smatch encoded, described;
  ASSERT_TRUE(std::regex_search(one.err, encoded, std::regex("motion +([0-9]+) segments?")))
      << one.err;
  const testing::CliRun one_info = testing::RunMeshvid("info '" + dir.File("one.mvid") + "'", dir);
  ASSERT_TRUE(std::regex_search(one_info.out, described,
                                std::regex("motion +([0-9]+) segments? in key group 0")))
      << one_info.out;
  EXPECT_EQ(encoded[1], described[1]);
}

TEST(CliConventionsTest, JsonGoesToAFileOrStdoutAndSummariesToStderr) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  for (const std::string& command :
       {"info '" + kThreeKeyGroups + "' --json -",
        "decode '" + kThreeKeyGroups + "' --no-write -q --json -",
        "export '" + kThreeKeyGroups + "' -o '" + dir.File("e.glb") + "' -q --json -",
        "render '" + kThreeKeyGroups + "' -o '" + dir.File("r.png") + "' --size 32x32 -q --json -",
        "simulate scene:cloth -o '" + dir.File("cap2") +
            "' --frames 0:1 --res 80x60 -q --json -"}) {
    const testing::CliRun run = testing::RunMeshvid(command, dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(nlohmann::json::accept(run.out)) << command << "\n" << run.out;
  }
  const testing::CliRun to_file = testing::RunMeshvid(
      "info '" + kThreeKeyGroups + "' --json '" + dir.File("i.json") + "'", dir);
  ASSERT_EQ(to_file.exit_code, 0) << to_file.err;
  EXPECT_EQ(nlohmann::json::parse(testing::ReadFile(dir.File("i.json")))["frames"], 12);
  EXPECT_NE(to_file.out.find("key groups     3"), std::string::npos) << to_file.out;

  // Commands that make files print their summary on stderr; stdout stays for machine output.
  const testing::CliRun simulate = testing::RunMeshvid(
      "simulate scene:cloth -o '" + dir.File("cap") + "' --frames 0:1 --res 160x120", dir);
  ASSERT_EQ(simulate.exit_code, 0) << simulate.err;
  EXPECT_EQ(simulate.out, "");
  EXPECT_NE(simulate.err.find("Simulated 1 frame x 3 views"), std::string::npos) << simulate.err;
  const testing::CliRun fuse = testing::RunMeshvid(
      "fuse '" + dir.File("cap") + "' --out '" + dir.File("fused/f{frame}.ply") + "' --json -",
      dir);
  ASSERT_EQ(fuse.exit_code, 0) << fuse.err;
  EXPECT_TRUE(nlohmann::json::accept(fuse.out)) << fuse.out;
  EXPECT_NE(fuse.err.find("Fused frames 0..0"), std::string::npos) << fuse.err;
  EXPECT_TRUE(std::filesystem::exists(dir.File("fused/f0.ply")));
  const testing::CliRun eval =
      testing::RunMeshvid("eval --ref '" + dir.File("cap/ground_truth.obj") + "' --test '" +
                              dir.File("cap") + "' --samples 1000 -q --json -",
                          dir);
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  EXPECT_TRUE(nlohmann::json::accept(eval.out)) << eval.out;
  EXPECT_NE(eval.err.find("D1 PSNR"), std::string::npos) << eval.err;  // the table

  // The commands are listed in the order of the work.
  const std::string help = testing::RunMeshvid("--help", dir).out;
  std::size_t last = 0;
  for (const char* command :
       {"simulate", "encode", "info", "decode", "export", "render", "eval", "fuse", "bench"}) {
    const std::size_t at = help.find("\n  " + std::string(command) + " ");
    ASSERT_NE(at, std::string::npos) << command;
    EXPECT_GT(at, last) << command;
    last = at;
  }
}

TEST(CliConventionsTest, ALogGetsAProgressLineEveryFiveSecondsAtMost) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  SimulateArmBlock(dir, 3);
  const auto start = std::chrono::steady_clock::now();
  const testing::CliRun run =
      testing::RunMeshvid("encode '" + dir.File("cap") + "' -o '" + dir.File("a.mvid") + "'", dir);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::size_t progress_lines = 0;
  const std::regex progress(": [0-9]+/[0-9]+\n");
  for (auto it = std::sregex_iterator(run.err.begin(), run.err.end(), progress);
       it != std::sregex_iterator(); ++it) {
    ++progress_lines;
  }
  EXPECT_LE(progress_lines, static_cast<std::size_t>(seconds / 5.0) + 1) << run.err;
}

TEST(CliConventionsTest, DecodeWritesVertexNormalsWhenAsked) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  for (const std::string extension : {".ply", ".obj"}) {
    const testing::CliRun with =
        testing::RunMeshvid("decode '" + kThreeKeyGroups + "' --frames 6 --normals -q -o '" +
                                dir.File("n{frame}" + extension) + "'",
                            dir);
    ASSERT_EQ(with.exit_code, 0) << with.err;
    const StatusOr<TriangleMesh> mesh = ReadMesh(dir.File("n6" + extension));
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    ASSERT_EQ(mesh->normals.size(), mesh->vertex_count()) << extension;
    // The sphere's normals point outwards.
    std::size_t outwards = 0;
    for (std::size_t v = 0; v < mesh->vertex_count(); ++v) {
      outwards += mesh->normals[v].dot(mesh->positions[v]) > 0;
    }
    EXPECT_GT(outwards, 9 * mesh->vertex_count() / 10) << extension;
    ASSERT_EQ(testing::RunMeshvid("decode '" + kThreeKeyGroups + "' --frames 6 -q -o '" +
                                      dir.File("p{frame}" + extension) + "'",
                                  dir)
                  .exit_code,
              0);
    EXPECT_TRUE(ReadMesh(dir.File("p6" + extension))->normals.empty()) << extension;
  }
}

TEST(CliConventionsTest, EncodeNeedsOnlyTheViewFilesOfItsFramesAndCreatesItsFolder) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  SimulateArmBlock(dir, 3);
  std::filesystem::remove(dir.File("cap/f0002_v1.ply"));
  const testing::CliRun part = testing::RunMeshvid(
      "encode '" + dir.File("cap") + "' --frames 0:1 -q -o '" + dir.File("new/dir/a.mvid") + "'",
      dir);
  EXPECT_EQ(part.exit_code, 0) << part.err;
  EXPECT_TRUE(std::filesystem::exists(dir.File("new/dir/a.mvid")));
  const testing::CliRun whole = testing::RunMeshvid(
      "encode '" + dir.File("cap") + "' -q -o '" + dir.File("b.mvid") + "'", dir);
  EXPECT_EQ(whole.exit_code, 1);
  EXPECT_NE(whole.err.find("1 of the 9 view files are missing, the first is " +
                           dir.File("cap/f0002_v1.ply") + " (frame 2, view 1)"),
            std::string::npos)
      << whole.err;
  const testing::CliRun fuse =
      testing::RunMeshvid("fuse '" + dir.File("cap") + "' --frames 2", dir);
  EXPECT_EQ(fuse.exit_code, 1);
  EXPECT_NE(fuse.err.find("1 of the 3 view files of frames 2..2 are missing"), std::string::npos)
      << fuse.err;
}

TEST(CliConventionsTest, SimulateSaysWhereTheCamerasLookAndWhenTheSubjectIsSideOn) {
  MESHVID_REQUIRE_CLI();
  MESHVID_REQUIRE_SHARED_DATA();
  testing::TempDir dir;
  const std::string samba = shared_data + "/sequences/samba.obj";
  const testing::CliRun front = testing::RunMeshvid(
      "simulate '" + samba + "' -o '" + dir.File("a") + "' --frames 0:1 --res 160x120", dir);
  ASSERT_EQ(front.exit_code, 0) << front.err;
  EXPECT_NE(front.err.find("The rig's centre looks at the subject from +z (azimuth 0 deg"),
            std::string::npos)
      << front.err;
  EXPECT_NE(front.err.find("it may be side-on to the cameras (--azimuth 90"), std::string::npos)
      << front.err;
  const testing::CliRun turned =
      testing::RunMeshvid("simulate '" + samba + "' -o '" + dir.File("b") +
                              "' --frames 0:1 --res 160x120 "
                              "--azimuth 90",
                          dir);
  ASSERT_EQ(turned.exit_code, 0) << turned.err;
  EXPECT_NE(turned.err.find("looks at the subject from +x (azimuth 90 deg"), std::string::npos)
      << turned.err;
  EXPECT_EQ(turned.err.find("side-on"), std::string::npos) << turned.err;
}

TEST(CliConventionsTest, AnEncodeHeldToTooFewKeyGroupsSaysWhichFramesItCouldNotExplain) {
  MESHVID_REQUIRE_CLI();
  testing::TempDir dir;
  SimulateArmBlock(dir, 5);
  const testing::CliRun free_run = testing::RunMeshvid(
      "encode '" + dir.File("cap") + "' -q -o '" + dir.File("free.mvid") + "' --json -", dir);
  ASSERT_EQ(free_run.exit_code, 0) << free_run.err;
  const nlohmann::json free = nlohmann::json::parse(free_run.out);
  // The arm swings fast over the first frames: the encoder wants a fresh base among them.
  ASSERT_GT(free["key_groups"].size(), 1u) << free_run.out;
  for (const nlohmann::json& group : free["key_groups"]) EXPECT_TRUE(group["held_frames"].empty());

  const testing::CliRun held_run =
      testing::RunMeshvid("encode '" + dir.File("cap") + "' -o '" + dir.File("held.mvid") +
                              "' --max-key-groups 1 --json '" + dir.File("held.json") + "'",
                          dir);
  ASSERT_EQ(held_run.exit_code, 0) << held_run.err;
  const nlohmann::json held = nlohmann::json::parse(testing::ReadFile(dir.File("held.json")));
  ASSERT_EQ(held["key_groups"].size(), 1u);
  const nlohmann::json& frames = held["key_groups"][0]["held_frames"];
  ASSERT_FALSE(frames.empty());
  // Held to one base the displacements reach farther (detail_max_distance), so the first frame
  // the base does not explain is no earlier than where the free encode started a new one.
  EXPECT_GE(frames[0]["frame"].get<int>(), free["key_groups"][1]["first_frame"].get<int>());
  EXPECT_GT(frames[0]["loss_db"].get<double>(), 0);
  EXPECT_NE(held_run.err.find("warning       --max-key-groups 1: key group 0 keeps "),
            std::string::npos)
      << held_run.err;
  EXPECT_NE(held_run.err.find("its base does not explain"), std::string::npos) << held_run.err;
}

}  // namespace
}  // namespace meshvid
