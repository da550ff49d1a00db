#include "tools/sim/scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <utility>

#include <Eigen/Geometry>

namespace meshvid {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// A procedural scene: fixed triangles, positions computed in closed form per frame.
class ProceduralScene : public MeshSequence {
 public:
  using PoseFunction = std::function<void(double seconds, std::vector<Eigen::Vector3f>*)>;

  ProceduralScene(std::string name, const SceneOptions& options,
                  std::vector<Triangle> triangles, PoseFunction pose)
      : name_(std::move(name)),
        options_(options),
        triangles_(std::move(triangles)),
        pose_(std::move(pose)) {}

  int frame_count() const override { return options_.frame_count; }
  double frame_rate() const override { return options_.frame_rate; }
  bool fixed_connectivity() const override { return true; }
  std::string description() const override {
    return "scene:" + name_ + " (procedural, " + std::to_string(options_.frame_count) +
           " frames)";
  }

  StatusOr<TriangleMesh> Frame(int t) override {
    if (t < 0 || t >= options_.frame_count) {
      return InvalidArgumentError(description() + ": frame " + std::to_string(t) +
                                  " is out of range [0, " +
                                  std::to_string(options_.frame_count) + ")");
    }
    TriangleMesh mesh;
    mesh.triangles = triangles_;
    const double rate = options_.frame_rate > 0 ? options_.frame_rate : 25.0;
    pose_(t / rate, &mesh.positions);
    return mesh;
  }

 private:
  std::string name_;
  SceneOptions options_;
  std::vector<Triangle> triangles_;
  PoseFunction pose_;
};

double SmoothStep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// Rest geometry of one primitive being assembled.
struct Builder {
  std::vector<Eigen::Vector3d> positions;
  std::vector<Triangle> triangles;

  std::uint32_t Add(const Eigen::Vector3d& p) {
    positions.push_back(p);
    return static_cast<std::uint32_t>(positions.size() - 1);
  }
  /// Adds a triangle, flipped if needed so its normal points away from `inside`.
  void AddOutward(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                  const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& inside) {
    const Eigen::Vector3d pa = positions[a], pb = positions[b], pc = positions[c];
    const Eigen::Vector3d centroid = (pa + pb + pc) / 3.0;
    const Eigen::Vector3d normal = (pb - pa).cross(pc - pa);
    if (normal.dot(centroid - inside(centroid)) < 0) std::swap(b, c);
    triangles.emplace_back(a, b, c);
  }
};

// Arm-block dimensions (metres), in the arm's local frame: the arm runs along +x from the
// shoulder at the origin.
constexpr double kArmLength = 0.57;
constexpr double kElbowX = 0.30;
constexpr double kWristX = 0.57;
constexpr int kTubeAround = 40;
constexpr int kTubeAlong = 64;
const Eigen::Vector3d kHandCentre(0.63, 0.0, 0.0);
const Eigen::Vector3d kHandRadii(0.06, 0.03, 0.045);
const Eigen::Vector3d kBlockCentre(0.63, -0.075, 0.0);
const Eigen::Vector3d kBlockSize(0.14, 0.10, 0.10);
const Eigen::Vector3d kShoulderWorld(-0.3, 1.4, 0.0);

enum Bone { kUpperArm = 0, kForearm = 1, kHand = 2, kBlock = 3 };

/// The arm-block rest mesh plus, per vertex, its skinning (forearm weight for the tube) and
/// rigid piece.
struct ArmBlockRig {
  std::vector<Eigen::Vector3d> rest;
  std::vector<Triangle> triangles;
  std::vector<double> forearm_weight;  // tube vertices: LBS weight of the forearm
  std::vector<Bone> bone;              // dominant bone / piece
};

void AppendBuilder(const Builder& builder, ArmBlockRig* rig,
                   const std::function<std::pair<Bone, double>(const Eigen::Vector3d&)>& skin) {
  const auto offset = static_cast<std::uint32_t>(rig->rest.size());
  for (const Eigen::Vector3d& p : builder.positions) {
    rig->rest.push_back(p);
    const auto [bone, weight] = skin(p);
    rig->bone.push_back(bone);
    rig->forearm_weight.push_back(weight);
  }
  for (const Triangle& t : builder.triangles) {
    rig->triangles.emplace_back(t[0] + offset, t[1] + offset, t[2] + offset);
  }
}

Builder MakeTube() {
  Builder b;
  for (int j = 0; j < kTubeAlong; ++j) {
    const double x = kArmLength * j / (kTubeAlong - 1);
    // Tapering radius with a slight muscle bulge on the upper arm.
    const double radius = 0.05 - 0.012 * x / kArmLength +
                          0.006 * std::sin(std::numbers::pi * std::clamp(x / kElbowX, 0.0, 1.0));
    for (int i = 0; i < kTubeAround; ++i) {
      const double angle = kTwoPi * i / kTubeAround;
      b.Add({x, radius * std::cos(angle), radius * std::sin(angle)});
    }
  }
  const std::uint32_t start = b.Add({0, 0, 0});
  const std::uint32_t end = b.Add({kArmLength, 0, 0});
  auto axis = [](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(std::clamp(p.x(), 0.01, kArmLength - 0.01), 0, 0);
  };
  auto index = [](int j, int i) {
    return static_cast<std::uint32_t>(j * kTubeAround + (i % kTubeAround));
  };
  for (int j = 0; j + 1 < kTubeAlong; ++j) {
    for (int i = 0; i < kTubeAround; ++i) {
      b.AddOutward(index(j, i), index(j + 1, i), index(j + 1, i + 1), axis);
      b.AddOutward(index(j, i), index(j + 1, i + 1), index(j, i + 1), axis);
    }
  }
  for (int i = 0; i < kTubeAround; ++i) {
    b.AddOutward(start, index(0, i), index(0, i + 1), axis);
    b.AddOutward(end, index(kTubeAlong - 1, i), index(kTubeAlong - 1, i + 1), axis);
  }
  return b;
}

Builder MakeEllipsoid(const Eigen::Vector3d& centre, const Eigen::Vector3d& radii, int rings,
                      int segments) {
  Builder b;
  const std::uint32_t top = b.Add(centre + Eigen::Vector3d(0, radii.y(), 0));
  for (int r = 1; r < rings; ++r) {
    const double polar = std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double azimuth = kTwoPi * s / segments;
      b.Add(centre + Eigen::Vector3d(radii.x() * std::sin(polar) * std::cos(azimuth),
                                     radii.y() * std::cos(polar),
                                     radii.z() * std::sin(polar) * std::sin(azimuth)));
    }
  }
  const std::uint32_t bottom = b.Add(centre - Eigen::Vector3d(0, radii.y(), 0));
  auto at = [&](int r, int s) {
    return static_cast<std::uint32_t>(1 + (r - 1) * segments + (s % segments));
  };
  auto inside = [&](const Eigen::Vector3d&) { return centre; };
  for (int s = 0; s < segments; ++s) {
    b.AddOutward(top, at(1, s), at(1, s + 1), inside);
    b.AddOutward(bottom, at(rings - 1, s), at(rings - 1, s + 1), inside);
    for (int r = 1; r + 1 < rings; ++r) {
      b.AddOutward(at(r, s), at(r + 1, s), at(r + 1, s + 1), inside);
      b.AddOutward(at(r, s), at(r + 1, s + 1), at(r, s + 1), inside);
    }
  }
  return b;
}

/// A watertight box subdivided into n x n quads per face (shared vertices on edges).
Builder MakeBox(const Eigen::Vector3d& centre, const Eigen::Vector3d& size, int n) {
  Builder b;
  std::map<std::array<int, 3>, std::uint32_t> lattice;
  auto vertex = [&](int i, int j, int k) {
    const std::array<int, 3> key{i, j, k};
    auto it = lattice.find(key);
    if (it != lattice.end()) return it->second;
    const Eigen::Vector3d unit(static_cast<double>(i) / n - 0.5, static_cast<double>(j) / n - 0.5,
                               static_cast<double>(k) / n - 0.5);
    const std::uint32_t index = b.Add(centre + unit.cwiseProduct(size));
    lattice.emplace(key, index);
    return index;
  };
  auto inside = [&](const Eigen::Vector3d&) { return centre; };
  for (int axis = 0; axis < 3; ++axis) {
    for (int side : {0, n}) {
      for (int u = 0; u < n; ++u) {
        for (int v = 0; v < n; ++v) {
          auto corner = [&](int du, int dv) {
            std::array<int, 3> c{};
            c[axis] = side;
            c[(axis + 1) % 3] = u + du;
            c[(axis + 2) % 3] = v + dv;
            return vertex(c[0], c[1], c[2]);
          };
          b.AddOutward(corner(0, 0), corner(1, 0), corner(1, 1), inside);
          b.AddOutward(corner(0, 0), corner(1, 1), corner(0, 1), inside);
        }
      }
    }
  }
  return b;
}

const ArmBlockRig& GetArmBlockRig() {
  static const ArmBlockRig* rig = [] {
    auto* r = new ArmBlockRig;
    AppendBuilder(MakeTube(), r, [](const Eigen::Vector3d& p) {
      const double w = SmoothStep(kElbowX - 0.03, kElbowX + 0.03, p.x());
      return std::make_pair(w < 0.5 ? kUpperArm : kForearm, w);
    });
    AppendBuilder(MakeEllipsoid(kHandCentre, kHandRadii, 12, 24), r,
                  [](const Eigen::Vector3d&) { return std::make_pair(kHand, 1.0); });
    AppendBuilder(MakeBox(kBlockCentre, kBlockSize, 12), r,
                  [](const Eigen::Vector3d&) { return std::make_pair(kBlock, 1.0); });
    return r;
  }();
  return *rig;
}

/// The bone transforms of the arm-block scene at time `s` (seconds), world from local.
std::array<Eigen::Isometry3d, 3> ArmBlockBones(double s) {
  using Eigen::AngleAxisd;
  using Eigen::Translation3d;
  using Eigen::Vector3d;
  Eigen::Isometry3d upper = Eigen::Isometry3d::Identity();
  upper = Translation3d(kShoulderWorld) *
          AngleAxisd(0.3 * std::sin(kTwoPi * 0.25 * s), Vector3d::UnitY()) *
          AngleAxisd(0.25 * std::sin(kTwoPi * 0.4 * s), Vector3d::UnitZ());
  const Vector3d elbow(kElbowX, 0, 0), wrist(kWristX, 0, 0);
  Eigen::Isometry3d fore = upper * Translation3d(elbow) *
                           AngleAxisd(0.5 + 0.5 * std::sin(kTwoPi * 0.5 * s), Vector3d::UnitZ()) *
                           Translation3d(-elbow);
  Eigen::Isometry3d hand = fore * Translation3d(wrist) *
                           AngleAxisd(0.6 * std::sin(kTwoPi * 0.35 * s), Vector3d::UnitX()) *
                           Translation3d(-wrist);
  return {upper, fore, hand};
}

void PoseArmBlock(double s, std::vector<Eigen::Vector3f>* positions) {
  const ArmBlockRig& rig = GetArmBlockRig();
  const auto bones = ArmBlockBones(s);
  positions->resize(rig.rest.size());
  for (std::size_t v = 0; v < rig.rest.size(); ++v) {
    const Eigen::Vector3d& p = rig.rest[v];
    Eigen::Vector3d q;
    if (rig.bone[v] == kUpperArm || rig.bone[v] == kForearm) {
      const double w = rig.forearm_weight[v];
      q = (1.0 - w) * (bones[kUpperArm] * p) + w * (bones[kForearm] * p);
    } else {
      q = bones[kHand] * p;  // hand and block move together
    }
    (*positions)[v] = q.cast<float>();
  }
}

// Cloth grid.
constexpr int kClothColumns = 80;
constexpr int kClothRows = 80;
constexpr double kClothWidth = 1.0;
constexpr double kClothHeight = 0.8;
constexpr double kClothTop = 1.6;

void PoseCloth(double s, std::vector<Eigen::Vector3f>* positions) {
  positions->resize(static_cast<std::size_t>(kClothColumns) * kClothRows);
  const double fold = 0.5 - 0.5 * std::cos(kTwoPi * 0.2 * s);  // 0..1..0 every 5 s
  const double row_step = kClothHeight / (kClothRows - 1);
  double y = kClothTop, z_fold = 0;
  for (int j = 0; j < kClothRows; ++j) {
    const double v = static_cast<double>(j) / (kClothRows - 1);  // 0 at the pinned top
    if (j > 0) {
      // The lower part folds up towards the viewer (+z) as `fold` grows.
      const double bend = 1.4 * fold * SmoothStep(0.35, 0.75, v);
      y -= row_step * std::cos(bend);
      z_fold += row_step * std::sin(bend);
    }
    const double amplitude = std::pow(v, 1.5);
    for (int i = 0; i < kClothColumns; ++i) {
      const double u = static_cast<double>(i) / (kClothColumns - 1);
      const double x = kClothWidth * (u - 0.5) * (1.0 - 0.2 * fold);
      const double wave = 0.08 * amplitude * std::sin(kTwoPi * (1.2 * u + 0.8 * v - 0.7 * s)) +
                          0.04 * amplitude * std::sin(kTwoPi * (0.5 * u + 0.3 * s));
      const double pleat = 0.04 * fold * std::sin(kTwoPi * 3.0 * u) * (0.3 + 0.7 * v);
      (*positions)[static_cast<std::size_t>(j) * kClothColumns + i] =
          Eigen::Vector3d(x, y, z_fold + wave + pleat).cast<float>();
    }
  }
}

std::vector<Triangle> ClothTriangles() {
  std::vector<Triangle> triangles;
  auto at = [](int i, int j) { return static_cast<std::uint32_t>(j * kClothColumns + i); };
  for (int j = 0; j + 1 < kClothRows; ++j) {
    for (int i = 0; i + 1 < kClothColumns; ++i) {
      // Counter-clockwise seen from +z (rows go down in y).
      triangles.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j + 1));
      triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i + 1, j));
    }
  }
  return triangles;
}

}  // namespace

std::unique_ptr<MeshSequence> MakeArmBlockScene(const SceneOptions& options) {
  return std::make_unique<ProceduralScene>("arm-block", options, GetArmBlockRig().triangles,
                                           PoseArmBlock);
}

std::unique_ptr<MeshSequence> MakeClothScene(const SceneOptions& options) {
  return std::make_unique<ProceduralScene>("cloth", options, ClothTriangles(), PoseCloth);
}

StatusOr<std::unique_ptr<MeshSequence>> MakeScene(const std::string& name,
                                                  const SceneOptions& options) {
  if (options.frame_count < 1) {
    return InvalidArgumentError("scene:" + name + ": frame count must be at least 1");
  }
  if (name == "arm-block") return MakeArmBlockScene(options);
  if (name == "cloth") return MakeClothScene(options);
  return NotFoundError("unknown scene 'scene:" + name +
                       "'; built-in scenes are scene:arm-block and scene:cloth");
}

std::vector<std::string> ArmBlockVertexParts() {
  const ArmBlockRig& rig = GetArmBlockRig();
  std::vector<std::string> parts;
  parts.reserve(rig.bone.size());
  for (Bone bone : rig.bone) parts.push_back(bone == kBlock ? "block" : "arm");
  return parts;
}

std::vector<std::string> ArmBlockVertexPieces() {
  static const char* const kNames[] = {"upper_arm", "forearm", "hand", "block"};
  const ArmBlockRig& rig = GetArmBlockRig();
  std::vector<std::string> pieces;
  pieces.reserve(rig.bone.size());
  for (Bone bone : rig.bone) pieces.push_back(kNames[bone]);
  return pieces;
}

StatusOr<std::vector<std::string>> SceneVertexParts(const std::string& name) {
  if (name == "arm-block") return ArmBlockVertexParts();
  if (name == "cloth") {
    return std::vector<std::string>(static_cast<std::size_t>(kClothColumns) * kClothRows,
                                     "cloth");
  }
  return NotFoundError("unknown scene 'scene:" + name +
                       "'; built-in scenes are scene:arm-block and scene:cloth");
}

}  // namespace meshvid
