#include "codec/enc/tracking/motion_hint.h"

#include "codec/common/point_tree.h"

namespace meshvid {
namespace {

/// The node of `blend` that weighs most.
std::uint32_t StrongestNode(const VertexBlend& blend) {
  int strongest = 0;
  for (int a = 1; a < blend.count; ++a) {
    if (blend.influences[a].weight > blend.influences[strongest].weight) strongest = a;
  }
  return blend.influences[strongest].segment;
}

}  // namespace

MotionHint HintOf(int frame, const TriangleMesh& base, const MotionModel& motion,
                  std::span<const RigidTransform> previous,
                  std::span<const RigidTransform> tracked) {
  MotionHint hint;
  hint.frame = frame;
  PoseVertices(motion, tracked, base.positions, &hint.positions);
  hint.steps.resize(hint.positions.size());
  for (std::size_t v = 0; v < hint.positions.size(); ++v) {
    const std::uint32_t node = StrongestNode(motion.blends[v]);
    hint.steps[v] = Compose(tracked[node], Inverse(previous[node]));
  }
  return hint;
}

std::vector<RigidTransform> StepsBefore(const MotionHint& hint, const TriangleMesh& base,
                                        const MotionModel& motion) {
  if (hint.positions.empty()) return {};
  const PointCloud cloud{hint.positions};
  const PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kPointTreeLeafSize));
  std::vector<RigidTransform> before(motion.node_vertices.size());
  for (std::size_t j = 0; j < before.size(); ++j) {
    std::uint32_t nearest = 0;
    float squared = 0;
    tree.knnSearch(base.positions[motion.node_vertices[j]].data(), 1, &nearest, &squared);
    before[j] = Inverse(hint.steps[nearest]);
  }
  return before;
}

}  // namespace meshvid
