// glTF export: the skin and animation in the .glb pose the base mesh exactly as the decoder's
// motion does (linear blend skinning of the segment transforms), and each key group is shown
// only during its frames.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "codec/common/motion.h"
#include "codec/dec/mvid_decoder.h"
#include "tools/export/gltf_export.h"

namespace meshvid {
namespace {

using json = nlohmann::json;
// Three key groups: frames 0-4, 5-8, 9-11.
const std::string kGoldenV2 = std::string(MESHVID_GOLDEN_DIR) + "/sphere.v2.mvid";

/// A parsed .glb: its JSON and binary chunk.
struct Glb {
  json gltf;
  std::string bin;

  /// Accessor `a`'s components (float, unsigned byte, short or int) as floats.
  std::vector<float> Read(int a) const {
    const json& accessor = gltf["accessors"][a];
    const json& view = gltf["bufferViews"][accessor["bufferView"].get<int>()];
    const char* data = bin.data() + view["byteOffset"].get<std::size_t>();
    static const std::map<std::string, int> kWidth = {{"SCALAR", 1}, {"VEC3", 3}, {"VEC4", 4}};
    const std::size_t n = accessor["count"].get<std::size_t>() * kWidth.at(accessor["type"]);
    std::vector<float> out(n);
    for (std::size_t i = 0; i < n; ++i) {
      switch (accessor["componentType"].get<int>()) {
        case 5126: std::memcpy(&out[i], data + 4 * i, 4); break;
        case 5121: out[i] = static_cast<std::uint8_t>(data[i]); break;
        case 5123: {
          std::uint16_t v;
          std::memcpy(&v, data + 2 * i, 2);
          out[i] = static_cast<float>(v);
          break;
        }
        case 5125: {
          std::uint32_t v;
          std::memcpy(&v, data + 4 * i, 4);
          out[i] = static_cast<float>(v);
          break;
        }
        default: ADD_FAILURE() << "unexpected component type";
      }
    }
    return out;
  }
};

Glb Parse(const std::string& bytes) {
  Glb glb;
  std::uint32_t magic, json_length, bin_length;
  std::memcpy(&magic, bytes.data(), 4);
  EXPECT_EQ(magic, 0x46546C67u);
  std::memcpy(&json_length, bytes.data() + 12, 4);
  glb.gltf = json::parse(bytes.substr(20, json_length));
  std::memcpy(&bin_length, bytes.data() + 20 + json_length, 4);
  glb.bin = bytes.substr(28 + json_length, bin_length);
  return glb;
}

TEST(GltfExportTest, SkinAndAnimationPoseTheBaseAsTheDecoderDoes) {
  auto decoder = MvidDecoder::OpenFile(kGoldenV2);
  ASSERT_TRUE(decoder.ok()) << decoder.status().message();
  ExportOptions options;
  options.first_frame = 3;
  options.end_frame = 11;
  GltfExportStats stats;
  auto bytes = EncodeGltf(**decoder, options, {}, &stats);
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  EXPECT_EQ(stats.key_groups, 3u);
  EXPECT_EQ(stats.frames, 8u);
  const Glb glb = Parse(*bytes);
  ASSERT_EQ(glb.gltf["meshes"].size(), 3u);
  ASSERT_EQ(glb.gltf["skins"].size(), 3u);
  const json& animation = glb.gltf["animations"][0];

  for (int k = 0; k < 3; ++k) {
    const json& skin = glb.gltf["skins"][k];
    const json& primitive = glb.gltf["meshes"][k]["primitives"][0];
    const std::vector<float> positions = glb.Read(primitive["attributes"]["POSITION"]);
    const std::vector<float> joints = glb.Read(primitive["attributes"]["JOINTS_0"]);
    const std::vector<float> weights = glb.Read(primitive["attributes"]["WEIGHTS_0"]);
    const std::size_t vertices = positions.size() / 3;
    // Every joint's rotation and translation track, and the key group node's scale track.
    std::map<int, std::vector<float>> rotation, translation;
    std::vector<float> scale_times, scales;
    std::vector<float> times;
    for (const json& channel : animation["channels"]) {
      const json& sampler = animation["samplers"][channel["sampler"].get<int>()];
      const int node = channel["target"]["node"];
      const std::string path = channel["target"]["path"];
      bool ours = false;  // a joint of this key group's skin
      for (const json& joint : skin["joints"]) ours = ours || joint.get<int>() == node;
      if (path == "scale" && node == skin["skeleton"].get<int>()) {
        scale_times = glb.Read(sampler["input"]);
        scales = glb.Read(sampler["output"]);
        EXPECT_EQ(sampler["interpolation"], "STEP");
      } else if (path == "rotation" && ours) {
        rotation[node] = glb.Read(sampler["output"]);
        times = glb.Read(sampler["input"]);
      } else if (path == "translation" && ours) {
        translation[node] = glb.Read(sampler["output"]);
      }
    }
    // Key group k spans frames [first, end) of the export's 3..10; time 0 is frame 3.
    const int first = k == 0 ? 3 : (k == 1 ? 5 : 9), end = k == 0 ? 5 : (k == 1 ? 9 : 11);
    ASSERT_EQ(times.size(), static_cast<std::size_t>(end - first));
    EXPECT_FLOAT_EQ(times[0], (first - 3) / 25.0f);
    // Shown exactly during its frames.
    for (std::size_t i = 0; i < scale_times.size(); ++i) {
      const float t = scale_times[i] * 25.0f + 3;
      const bool inside = t >= first - 1e-3f && t < end - 1e-3f;
      EXPECT_EQ(scales[3 * i], inside ? 1.0f : 0.0f) << "key group " << k << " at frame " << t;
    }
    for (int frame = first; frame < end; ++frame) {
      auto transforms = (*decoder)->DecodeTransforms(frame);
      ASSERT_TRUE(transforms.ok());
      std::vector<Eigen::Vector3f> expected;
      PoseVertices((*decoder)->motion(), *transforms, (*decoder)->base_mesh().positions,
                   &expected);
      ASSERT_EQ(expected.size(), vertices);
      const int sample = frame - first;
      for (std::size_t v = 0; v < vertices; ++v) {
        const Eigen::Vector3f rest(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
        Eigen::Vector3f posed = Eigen::Vector3f::Zero();
        for (int i = 0; i < 4; ++i) {
          const int node = skin["joints"][static_cast<int>(joints[4 * v + i])];
          const float* q = &rotation[node][4 * sample];
          const float* t = &translation[node][3 * sample];
          const Eigen::Quaternionf r(q[3], q[0], q[1], q[2]);
          posed += weights[4 * v + i] * (r * rest + Eigen::Vector3f(t[0], t[1], t[2]));
        }
        ASSERT_LT((posed - expected[v]).norm(), 1e-5f) << "key group " << k << " frame "
                                                       << frame << " vertex " << v;
      }
    }
  }
}

// Vertex colour: COLOR_0 of each key group's primitive holds its base vertices' colours at
// the run's first frame, linearised from the decoded (sRGB) colour as glTF defines it, as
// normalised unsigned shorts with alpha 1.
TEST(GltfExportTest, VertexColourIsTheDecodedColourMadeLinear) {
  const std::string golden = std::string(MESHVID_GOLDEN_DIR) + "/sphere.colour.mvid";
  auto decoder = MvidDecoder::OpenFile(golden);
  ASSERT_TRUE(decoder.ok()) << decoder.status().ToString();
  ASSERT_TRUE((*decoder)->info().colour);
  auto bytes = EncodeGltf(**decoder, {});
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  const Glb glb = Parse(*bytes);
  const json& meshes = glb.gltf["meshes"];
  const std::uint32_t first_frames[] = {0, 4};  // the golden file's two key groups
  ASSERT_EQ(meshes.size(), 2u);
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const json& attributes = meshes[k]["primitives"][0]["attributes"];
    ASSERT_TRUE(attributes.contains("COLOR_0")) << "key group " << k;
    const json& accessor = glb.gltf["accessors"][attributes["COLOR_0"].get<int>()];
    EXPECT_EQ(accessor["componentType"], 5123);
    EXPECT_EQ(accessor["normalized"], true);
    EXPECT_EQ(accessor["type"], "VEC4");
    const int positions = attributes["POSITION"].get<int>();
    ASSERT_EQ(accessor["count"], glb.gltf["accessors"][positions]["count"]);
    const std::vector<float> rgba = glb.Read(attributes["COLOR_0"].get<int>());
    std::vector<Colour> colours;
    ASSERT_TRUE((*decoder)->DecodeColours(first_frames[k], 0, &colours).ok());
    ASSERT_EQ(rgba.size(), 4 * colours.size());
    for (std::size_t v = 0; v < colours.size(); ++v) {
      for (int c = 0; c < 3; ++c) {
        const double srgb = colours[v][c] / 255.0;
        const double linear =
            srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4);
        EXPECT_NEAR(rgba[4 * v + c] / 65535.0, linear, 1.0 / 65535) << "vertex " << v;
      }
      EXPECT_EQ(rgba[4 * v + 3], 65535.0f);
    }
  }
}

}  // namespace
}  // namespace meshvid
