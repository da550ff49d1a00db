// Procedural ground-truth scenes for the capture simulator: deterministic animated meshes with
// fixed connectivity, in metres, y up, facing +z.
//  - "arm-block": an upper arm and forearm articulated at the elbow, a hand turning at the
//    wrist and gripping a box that moves rigidly with it (the paper's composite scene);
//  - "cloth": a hanging sheet that waves and folds (non-rigid).
#ifndef MESHVID_TOOLS_SIM_SCENES_H_
#define MESHVID_TOOLS_SIM_SCENES_H_

#include <memory>
#include <string>
#include <vector>

#include "format/status.h"
#include "tools/io/mesh_sequence.h"

namespace meshvid {

/// Length and rate of a procedural scene.
struct SceneOptions {
  int frame_count = 100;
  double frame_rate = 25.0;
};

/// The arm-block scene: ~4k vertices in four rigid pieces (upper arm, forearm, hand, block),
/// the arm's skin blended smoothly across the elbow.
std::unique_ptr<MeshSequence> MakeArmBlockScene(const SceneOptions& options = {});

/// The cloth scene: an 80 x 80 vertex sheet (1.0 x 0.8 m) hanging from its top edge, waving
/// and folding.
std::unique_ptr<MeshSequence> MakeClothScene(const SceneOptions& options = {});

/// Makes the built-in scene `name` ("arm-block" or "cloth", without "scene:").
StatusOr<std::unique_ptr<MeshSequence>> MakeScene(const std::string& name,
                                                  const SceneOptions& options = {});

/// Per vertex of the arm-block scene, the object it belongs to: "arm" (upper arm, forearm and
/// hand: articulated) or "block" (the gripped box: rigid).
std::vector<std::string> ArmBlockVertexParts();

/// Per vertex of the arm-block scene, its rigid piece: "upper_arm", "forearm", "hand" or
/// "block". Arm vertices in the elbow's blend zone are labelled by their dominant bone.
std::vector<std::string> ArmBlockVertexPieces();

/// Per vertex of scene `name`, its part label (arm-block: ArmBlockVertexParts(); cloth:
/// "cloth" everywhere).
StatusOr<std::vector<std::string>> SceneVertexParts(const std::string& name);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_SIM_SCENES_H_
