#include "tools/export/gltf_export.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/common/motion.h"
#include "format/output_file.h"

namespace meshvid {
namespace {

/// The linear value in [0, 1] of an 8-bit sRGB-encoded channel (IEC 61966-2-1).
double SrgbToLinear(std::uint8_t code) {
  const double v = code / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

using json = nlohmann::json;

// glTF constants.
constexpr int kFloat = 5126, kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

/// The binary chunk and the JSON arrays that describe it.
class GltfBuilder {
 public:
  /// Appends `bytes` as a buffer view (4-byte aligned); returns its index.
  int AddView(const void* bytes, std::size_t size, int target) {
    while (bin_.size() % 4 != 0) bin_.push_back('\0');
    json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", size}};
    if (target != 0) view["target"] = target;
    bin_.append(static_cast<const char*>(bytes), size);
    views_.push_back(view);
    return static_cast<int>(views_.size()) - 1;
  }

  /// An accessor over a whole view; `min`/`max` are written when given.
  int AddAccessor(int view, int component, std::size_t count, const char* type,
                  const json& min = nullptr, const json& max = nullptr) {
    json accessor = {{"bufferView", view}, {"componentType", component}, {"count", count},
                     {"type", type}};
    if (!min.is_null()) accessor["min"] = min, accessor["max"] = max;
    accessors_.push_back(accessor);
    return static_cast<int>(accessors_.size()) - 1;
  }

  /// Marks accessor `accessor` as normalised (integers read as fractions of their range).
  void NormaliseAccessor(int accessor) { accessors_[accessor]["normalized"] = true; }

  /// Float vectors (VEC3/VEC4 or SCALAR) with their bounds.
  template <int N>
  int AddFloats(const std::vector<std::array<float, N>>& values, const char* type, int target,
                bool bounds) {
    const int view = AddView(values.data(), values.size() * sizeof(values[0]), target);
    if (!bounds) return AddAccessor(view, kFloat, values.size(), type);
    std::array<float, N> lo, hi;
    lo.fill(std::numeric_limits<float>::max());
    hi.fill(std::numeric_limits<float>::lowest());
    for (const auto& v : values) {
      for (int i = 0; i < N; ++i) lo[i] = std::min(lo[i], v[i]), hi[i] = std::max(hi[i], v[i]);
    }
    return AddAccessor(view, kFloat, values.size(), type, lo, hi);
  }

  json& root() { return root_; }

  /// The .glb file: header, JSON chunk (space padded), binary chunk (zero padded).
  std::string Finish() {
    while (bin_.size() % 4 != 0) bin_.push_back('\0');
    root_["buffers"] = json::array({{{"byteLength", bin_.size()}}});
    root_["bufferViews"] = views_;
    root_["accessors"] = accessors_;
    std::string text = root_.dump();
    while (text.size() % 4 != 0) text.push_back(' ');
    std::string glb;
    auto u32 = [&glb](std::uint32_t v) {
      for (int i = 0; i < 4; ++i) glb.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
    };
    u32(0x46546C67);  // "glTF"
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin_.size()));
    u32(static_cast<std::uint32_t>(text.size()));
    u32(0x4E4F534A);  // "JSON"
    glb += text;
    u32(static_cast<std::uint32_t>(bin_.size()));
    u32(0x004E4942);  // "BIN\0"
    glb += bin_;
    return glb;
  }

 private:
  std::string bin_;
  json views_ = json::array();
  json accessors_ = json::array();
  json root_;
};

using Vec3 = std::array<float, 3>;
using Vec4 = std::array<float, 4>;
using Scalar = std::array<float, 1>;

Vec3 ToArray(const Eigen::Vector3f& v) { return {v.x(), v.y(), v.z()}; }
Vec4 ToArray(const Eigen::Quaternionf& q) {
  const Eigen::Quaternionf n = q.normalized();
  return {n.x(), n.y(), n.z(), n.w()};
}

/// Adds key group `run`'s mesh, skin, nodes and animation to `gltf`; `time` maps a frame to
/// seconds. Returns the number of joints.
StatusOr<std::uint32_t> AddKeyGroup(MvidDecoder& decoder, const KeyGroupRun& run,
                                    const ExportOptions& range, double frame_rate,
                                    GltfBuilder* gltf, json* nodes, json* meshes, json* skins,
                                    json* samplers, json* channels, json* scene_nodes,
                                    const ProgressCallback& progress, long* done) {
  auto time = [&](std::uint32_t frame) {
    return static_cast<float>((frame - range.first_frame) / frame_rate);
  };
  // Decode the run's transforms first: that makes its key group the decoder's current one.
  std::vector<std::vector<RigidTransform>> transforms;
  for (std::uint32_t frame = run.first; frame < run.end; ++frame) {
    MESHVID_ASSIGN_OR_RETURN(std::vector<RigidTransform> t, decoder.DecodeTransforms(frame));
    transforms.push_back(std::move(t));
    ++*done;
    if (!ReportProgress(progress, "exporting", *done,
                        static_cast<long>(range.end_frame - range.first_frame))) {
      return CancelledError("export cancelled");
    }
  }
  const TriangleMesh& base = decoder.base_mesh();
  const MotionModel& motion = decoder.motion();
  const std::uint32_t segments = motion.segment_count;
  if (segments == 0 || motion.blends.size() != base.vertex_count()) {
    return CorruptError("key group " + std::to_string(run.key_group) + " has no usable motion");
  }
  for (const auto& t : transforms) {
    if (t.size() != segments) {
      return CorruptError("key group " + std::to_string(run.key_group) +
                          ": a frame's transforms do not match its segments");
    }
  }

  // The mesh: the captured surface's triangles (hidden ones left out, as the decoder does).
  std::vector<std::uint32_t> indices;
  std::vector<Triangle> kept;
  for (std::size_t t = 0; t < base.triangle_count(); ++t) {
    if (!motion.surface_triangles.empty() && motion.surface_triangles[t] == 0) continue;
    kept.push_back(base.triangles[t]);
    for (int c = 0; c < 3; ++c) indices.push_back(base.triangles[t][c]);
  }
  if (kept.empty()) return CorruptError("a key group's base mesh has no surface triangles");
  std::vector<Eigen::Vector3f> normals;
  ComputeVertexNormals(base.positions, kept, &normals);
  std::vector<Vec3> positions_out, normals_out;
  std::vector<Vec4> weights_out;
  std::vector<std::uint16_t> joints_out;
  for (std::size_t v = 0; v < base.vertex_count(); ++v) {
    positions_out.push_back(ToArray(base.positions[v]));
    const Eigen::Vector3f n = normals[v].squaredNorm() > 0.5f ? normals[v] : Eigen::Vector3f::UnitY();
    normals_out.push_back(ToArray(n));
    const VertexBlend& blend = motion.blends[v];
    Vec4 weights = {0, 0, 0, 0};
    std::array<std::uint16_t, 4> joints = {0, 0, 0, 0};
    float sum = 0;
    for (int i = 0; i < blend.count && i < kMaxInfluences; ++i) {
      joints[i] = static_cast<std::uint16_t>(blend.influences[i].segment);
      weights[i] = blend.influences[i].weight;
      sum += weights[i];
    }
    if (!(sum > 0)) weights = {1, 0, 0, 0}, sum = 1;
    for (float& w : weights) w /= sum;
    weights_out.push_back(weights);
    joints_out.insert(joints_out.end(), joints.begin(), joints.end());
  }
  const int position = gltf->AddFloats<3>(positions_out, "VEC3", kArrayBuffer, true);
  const int normal = gltf->AddFloats<3>(normals_out, "VEC3", kArrayBuffer, false);
  const int weight = gltf->AddFloats<4>(weights_out, "VEC4", kArrayBuffer, false);
  int joint;
  if (segments <= 256) {
    std::vector<std::uint8_t> bytes(joints_out.begin(), joints_out.end());
    joint = gltf->AddAccessor(gltf->AddView(bytes.data(), bytes.size(), kArrayBuffer),
                              kUnsignedByte, base.vertex_count(), "VEC4");
  } else {
    joint = gltf->AddAccessor(
        gltf->AddView(joints_out.data(), joints_out.size() * 2, kArrayBuffer), kUnsignedShort,
        base.vertex_count(), "VEC4");
  }
  const int index = gltf->AddAccessor(
      gltf->AddView(indices.data(), indices.size() * 4, kElementArrayBuffer), kUnsignedInt,
      indices.size(), "SCALAR");
  json attributes = {
      {"POSITION", position}, {"NORMAL", normal}, {"JOINTS_0", joint}, {"WEIGHTS_0", weight}};
  if (decoder.info().colour) {
    // The base vertices' colours at the run's first frame (glTF's vertex colour does not
    // change over an animation). glTF's vertex colour is linear and meshvid's is display
    // (sRGB) colour, so each channel is linearised and kept as a normalised unsigned short,
    // which keeps the dark tones' steps; RGBA keeps every element 4-byte aligned.
    std::vector<Colour> colours;
    MESHVID_RETURN_IF_ERROR(decoder.DecodeColours(run.first, 0, &colours));
    std::vector<std::uint16_t> rgba;
    for (std::size_t v = 0; v < base.vertex_count(); ++v) {
      for (int c = 0; c < 3; ++c) {
        rgba.push_back(static_cast<std::uint16_t>(std::lround(SrgbToLinear(colours[v][c]) * 65535)));
      }
      rgba.push_back(65535);
    }
    const int colour = gltf->AddAccessor(
        gltf->AddView(rgba.data(), rgba.size() * sizeof(std::uint16_t), kArrayBuffer),
        kUnsignedShort, base.vertex_count(), "VEC4");
    gltf->NormaliseAccessor(colour);
    attributes["COLOR_0"] = colour;
  }
  const std::string name = "key group " + std::to_string(run.key_group);
  meshes->push_back(
      {{"name", name},
       {"primitives",
        json::array({{{"attributes", attributes}, {"indices", index}, {"mode", 4}}})}});

  // Nodes: the key group's root (its visibility), one joint per segment under it, and the
  // skinned mesh at the scene's root (glTF ignores a skinned mesh node's own transform).
  const int group_node = static_cast<int>(nodes->size());
  const int first_joint = group_node + 1;
  json children = json::array(), joint_list = json::array();
  for (std::uint32_t s = 0; s < segments; ++s) {
    children.push_back(first_joint + static_cast<int>(s));
    joint_list.push_back(first_joint + static_cast<int>(s));
  }
  const bool visible_at_start = run.first == range.first_frame;
  nodes->push_back({{"name", name}, {"children", children},
                    {"scale", visible_at_start ? Vec3{1, 1, 1} : Vec3{0, 0, 0}}});
  for (std::uint32_t s = 0; s < segments; ++s) {
    nodes->push_back({{"name", name + " segment " + std::to_string(s)},
                      {"rotation", ToArray(transforms[0][s].rotation)},
                      {"translation", ToArray(transforms[0][s].translation)}});
  }
  const int skin = static_cast<int>(skins->size());
  skins->push_back({{"name", name}, {"joints", joint_list}, {"skeleton", group_node}});
  const int mesh_node = static_cast<int>(nodes->size());
  nodes->push_back({{"name", name + " surface"},
                    {"mesh", static_cast<int>(meshes->size()) - 1},
                    {"skin", skin}});
  scene_nodes->push_back(group_node);
  scene_nodes->push_back(mesh_node);

  // The animation: every segment's rotation and translation at each frame (LINEAR), and the
  // key group's scale (STEP: 1 during its frames, 0 before and after).
  std::vector<Scalar> times;
  for (std::uint32_t frame = run.first; frame < run.end; ++frame) times.push_back({time(frame)});
  const int input = gltf->AddFloats<1>(times, "SCALAR", 0, true);
  for (std::uint32_t s = 0; s < segments; ++s) {
    std::vector<Vec4> rotations;
    std::vector<Vec3> translations;
    for (const auto& t : transforms) {
      Eigen::Quaternionf q = t[s].rotation.normalized();
      // Keep consecutive quaternions in one hemisphere so interpolation takes the short way.
      if (!rotations.empty()) {
        const Vec4& p = rotations.back();
        if (p[0] * q.x() + p[1] * q.y() + p[2] * q.z() + p[3] * q.w() < 0) q.coeffs() *= -1;
      }
      rotations.push_back({q.x(), q.y(), q.z(), q.w()});
      translations.push_back(ToArray(t[s].translation));
    }
    const int node = first_joint + static_cast<int>(s);
    const int r = gltf->AddFloats<4>(rotations, "VEC4", 0, false);
    const int t = gltf->AddFloats<3>(translations, "VEC3", 0, false);
    samplers->push_back({{"input", input}, {"output", r}, {"interpolation", "LINEAR"}});
    channels->push_back({{"sampler", samplers->size() - 1},
                         {"target", {{"node", node}, {"path", "rotation"}}}});
    samplers->push_back({{"input", input}, {"output", t}, {"interpolation", "LINEAR"}});
    channels->push_back({{"sampler", samplers->size() - 1},
                         {"target", {{"node", node}, {"path", "translation"}}}});
  }
  std::vector<Scalar> scale_times;
  std::vector<Vec3> scales;
  if (!visible_at_start) scale_times.push_back({0.0f}), scales.push_back({0, 0, 0});
  scale_times.push_back({time(run.first)}), scales.push_back({1, 1, 1});
  if (run.end < range.end_frame) scale_times.push_back({time(run.end)}), scales.push_back({0, 0, 0});
  const int scale_input = gltf->AddFloats<1>(scale_times, "SCALAR", 0, true);
  const int scale_output = gltf->AddFloats<3>(scales, "VEC3", 0, false);
  samplers->push_back({{"input", scale_input}, {"output", scale_output}, {"interpolation", "STEP"}});
  channels->push_back({{"sampler", samplers->size() - 1},
                       {"target", {{"node", group_node}, {"path", "scale"}}}});
  return segments;
}

}  // namespace

StatusOr<std::string> EncodeGltf(MvidDecoder& decoder, const ExportOptions& options,
                                 const ProgressCallback& progress, GltfExportStats* stats) {
  MESHVID_ASSIGN_OR_RETURN(const ExportOptions range,
                           ResolveExportOptions(decoder.info(), options));
  MESHVID_ASSIGN_OR_RETURN(const std::vector<KeyGroupRun> runs, KeyGroupRuns(decoder, range));
  const double frame_rate = decoder.info().frame_rate > 0 ? decoder.info().frame_rate : 25.0;
  GltfBuilder gltf;
  json nodes = json::array(), meshes = json::array(), skins = json::array();
  json samplers = json::array(), channels = json::array(), scene_nodes = json::array();
  GltfExportStats totals;
  long done = 0;
  for (const KeyGroupRun& run : runs) {
    MESHVID_ASSIGN_OR_RETURN(const std::uint32_t joints,
                             AddKeyGroup(decoder, run, range, frame_rate, &gltf, &nodes, &meshes,
                                         &skins, &samplers, &channels, &scene_nodes, progress,
                                         &done));
    totals.joints += joints;
  }
  json& root = gltf.root();
  root["asset"] = {{"version", "2.0"}, {"generator", "meshvid export"}};
  root["scene"] = 0;
  root["scenes"] = json::array({{{"name", "meshvid"}, {"nodes", scene_nodes}}});
  root["nodes"] = nodes;
  root["meshes"] = meshes;
  root["skins"] = skins;
  root["animations"] =
      json::array({{{"name", "motion"}, {"samplers", samplers}, {"channels", channels}}});
  std::string glb = gltf.Finish();
  totals.key_groups = static_cast<std::uint32_t>(runs.size());
  totals.frames = range.end_frame - range.first_frame;
  totals.bytes = glb.size();
  if (stats != nullptr) *stats = totals;
  return glb;
}

StatusOr<GltfExportStats> ExportGltf(MvidDecoder& decoder, const std::string& path,
                                     const ExportOptions& options,
                                     const ProgressCallback& progress) {
  GltfExportStats stats;
  MESHVID_ASSIGN_OR_RETURN(const std::string glb, EncodeGltf(decoder, options, progress, &stats));
  MESHVID_RETURN_IF_ERROR(WriteFileAtomically(path, glb));
  return stats;
}

}  // namespace meshvid
