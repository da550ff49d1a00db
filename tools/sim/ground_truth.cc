#include "tools/sim/ground_truth.h"

#include "tools/sim/scenes.h"

namespace meshvid {

namespace {
constexpr char kScenePrefix[] = "scene:";
}  // namespace

std::vector<std::string> BuiltInSceneNames() { return {"arm-block", "cloth"}; }

StatusOr<std::unique_ptr<MeshSequence>> OpenGroundTruth(const std::string& spec,
                                                        double frame_rate) {
  if (spec.rfind(kScenePrefix, 0) == 0) {
    SceneOptions options;
    if (frame_rate > 0) options.frame_rate = frame_rate;
    return MakeScene(spec.substr(sizeof(kScenePrefix) - 1), options);
  }
  if (spec.empty()) {
    return InvalidArgumentError(
        "no ground truth given: pass NAME.obj (with NAME.pc2 beside it), a folder of "
        "per-frame meshes, or scene:arm-block / scene:cloth");
  }
  return OpenMeshSequence(spec, frame_rate);
}

}  // namespace meshvid
