// A procedural albedo for simulated colour: a colour per ground-truth vertex, a function of
// the vertex's position in a reference pose, so the colour stays fixed to the surface as it
// moves.
#ifndef MESHVID_TOOLS_SIM_ALBEDO_H_
#define MESHVID_TOOLS_SIM_ALBEDO_H_

#include <vector>

#include "codec/common/mesh.h"

namespace meshvid {

/// Paints every vertex of `reference` (the ground truth in its reference pose) from its
/// position relative to the mesh's bounding box: a hue that drifts slowly across the
/// subject, modulated by a soft 3D checker whose squares are 1/16 of the box's largest side,
/// so the colour has both smooth gradients and edges. Channels stay within about [70, 210]
/// (never outside [24, 224]), which leaves room for a camera's exposure gain before 8 bits
/// clip. Deterministic.
std::vector<Colour> PaintAlbedo(const TriangleMesh& reference);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_SIM_ALBEDO_H_
