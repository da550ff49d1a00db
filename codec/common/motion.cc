#include "codec/common/motion.h"

#include <cmath>
#include <string>

namespace meshvid {

RigidTransform Compose(const RigidTransform& a, const RigidTransform& b) {
  RigidTransform result;
  result.rotation = (a.rotation * b.rotation).normalized();
  result.translation = a.rotation * b.translation + a.translation;
  return result;
}

RigidTransform Inverse(const RigidTransform& t) {
  RigidTransform result;
  result.rotation = t.rotation.conjugate();
  result.translation = -(result.rotation * t.translation);
  return result;
}

RigidTransform PredictConstantVelocity(const RigidTransform& before, const RigidTransform& last) {
  return Compose(Compose(last, Inverse(before)), last);
}

Status ValidateMotionModel(const MotionModel& model, std::size_t vertex_count) {
  if (model.segment_count == 0) return CorruptError("motion: no segments");
  if (!model.node_vertices.empty() && model.node_vertices.size() != model.segment_count) {
    return CorruptError("motion: " + std::to_string(model.node_vertices.size()) +
                        " deformation nodes for " + std::to_string(model.segment_count) +
                        " segments");
  }
  if (model.blends.size() != vertex_count) {
    return CorruptError("motion: " + std::to_string(model.blends.size()) +
                        " vertex blends for " + std::to_string(vertex_count) +
                        " base vertices");
  }
  for (std::size_t v = 0; v < model.blends.size(); ++v) {
    const VertexBlend& blend = model.blends[v];
    if (blend.count == 0 || blend.count > kMaxInfluences) {
      return CorruptError("motion: vertex " + std::to_string(v) + " has " +
                          std::to_string(blend.count) + " influences (1.." +
                          std::to_string(kMaxInfluences) + " allowed)");
    }
    float sum = 0;
    for (int i = 0; i < blend.count; ++i) {
      const BlendInfluence& influence = blend.influences[i];
      if (influence.segment >= model.segment_count) {
        return CorruptError("motion: vertex " + std::to_string(v) + " uses segment " +
                            std::to_string(influence.segment) + " of " +
                            std::to_string(model.segment_count));
      }
      if (!(influence.weight >= 0 && influence.weight <= 1)) {
        return CorruptError("motion: vertex " + std::to_string(v) + " has a weight outside [0, 1]");
      }
      sum += influence.weight;
    }
    if (std::abs(sum - 1.0f) > 1e-3f) {
      return CorruptError("motion: weights of vertex " + std::to_string(v) + " sum to " +
                          std::to_string(sum) + ", not 1");
    }
  }
  return Status::Ok();
}

void PoseVertices(const MotionModel& model, std::span<const RigidTransform> transforms,
                  std::span<const Eigen::Vector3f> base_positions,
                  std::vector<Eigen::Vector3f>* posed) {
  posed->resize(base_positions.size());
  // Rotation matrices once per segment rather than quaternion products per vertex.
  std::vector<Eigen::Matrix3f> rotations(transforms.size());
  for (std::size_t s = 0; s < transforms.size(); ++s) {
    rotations[s] = transforms[s].rotation.toRotationMatrix();
  }
  for (std::size_t v = 0; v < base_positions.size(); ++v) {
    const VertexBlend& blend = model.blends[v];
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    for (int i = 0; i < blend.count; ++i) {
      const BlendInfluence& influence = blend.influences[i];
      sum += influence.weight * (rotations[influence.segment] * base_positions[v] +
                                 transforms[influence.segment].translation);
    }
    (*posed)[v] = sum;
  }
}

MotionModel SingleSegmentModel(std::size_t vertex_count) {
  MotionModel model;
  model.segment_count = 1;
  VertexBlend blend;
  blend.count = 1;
  blend.influences[0] = {0, 1.0f};
  model.blends.assign(vertex_count, blend);
  return model;
}

}  // namespace meshvid
