// Ground truth for simulation and evaluation: an animated mesh from files, or a built-in
// procedural scene.
#ifndef MESHVID_TOOLS_SIM_GROUND_TRUTH_H_
#define MESHVID_TOOLS_SIM_GROUND_TRUTH_H_

#include <memory>
#include <string>
#include <vector>

#include "format/status.h"
#include "tools/io/mesh_sequence.h"

namespace meshvid {

/// Names of the built-in procedural scenes, without the "scene:" prefix ("arm-block", "cloth").
std::vector<std::string> BuiltInSceneNames();

/// Opens ground truth from "scene:NAME" (a built-in procedural scene) or anything
/// OpenMeshSequence accepts (NAME.obj + NAME.pc2, an OBJ-per-frame folder, a pattern).
StatusOr<std::unique_ptr<MeshSequence>> OpenGroundTruth(const std::string& spec,
                                                        double frame_rate = 25.0);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_SIM_GROUND_TRUTH_H_
