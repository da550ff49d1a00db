#include "codec/dec/key_group_geometry.h"

#include <utility>

#include "codec/common/deformation_graph.h"

namespace meshvid {

StatusOr<KeyGroupGeometry> KeyGroupGeometry::Create(TriangleMesh base,
                                                    std::span<const std::uint8_t> motion_payload,
                                                    int levels) {
  KeyGroupGeometry geometry;
  geometry.base_ = std::move(base);
  MESHVID_ASSIGN_OR_RETURN(DecodedMotion motion,
                           DecodeMotionModel(motion_payload, geometry.base_.vertex_count(),
                                             geometry.base_.triangle_count()));
  if (!motion.model.node_vertices.empty()) {
    MESHVID_RETURN_IF_ERROR(CompleteNodeBlends(geometry.base_, &motion.model));
  }
  geometry.motion_ = std::move(motion.model);
  geometry.quantization_ = motion.quantization;
  MESHVID_ASSIGN_OR_RETURN(geometry.subdivision_,
                           RegularSubdivision::Create(geometry.base_, levels));
  geometry.levels_ = levels;
  geometry.triangles_.resize(levels + 1);
  return geometry;
}

std::size_t KeyGroupGeometry::SurfaceTriangleCount() const {
  if (motion_.surface_triangles.empty()) return base_.triangle_count();
  std::size_t count = 0;
  for (std::uint8_t kept : motion_.surface_triangles) count += kept != 0;
  return count;
}

const std::vector<Triangle>& KeyGroupGeometry::Triangles(int level) {
  std::vector<Triangle>& triangles = triangles_[level];
  if (triangles.empty()) {
    triangles = subdivision_.Triangles(level);
    const std::vector<std::uint8_t>& surface = motion_.surface_triangles;
    if (!surface.empty()) {
      // Level l has 4^l triangles per base triangle, base triangle by base triangle.
      const std::size_t per_base = std::size_t(1) << (2 * level);
      std::size_t kept = 0;
      for (std::size_t t = 0; t < surface.size(); ++t) {
        if (!surface[t]) continue;
        for (std::size_t k = 0; k < per_base; ++k) {
          triangles[kept++] = triangles[t * per_base + k];
        }
      }
      triangles.resize(kept);
    }
  }
  return triangles;
}

const DisplacementLayout& KeyGroupGeometry::Layout(DisplacementPacking packing) {
  auto it = layouts_.find(packing);
  if (it == layouts_.end()) {
    it = layouts_.emplace(packing, DisplacementLayout::ForSubdivision(subdivision_, packing)).first;
  }
  return it->second;
}

StatusOr<const DisplacementLayout*> KeyGroupGeometry::CheckedLayout(DisplacementPacking packing,
                                                                    bool first_key_group,
                                                                    int header_width,
                                                                    int header_height) {
  const DisplacementLayout& layout = Layout(packing);
  if (first_key_group && (layout.width() != header_width || layout.height() != header_height)) {
    return CorruptError("displacement picture is " + std::to_string(header_width) + "x" +
                        std::to_string(header_height) + ", the packing of this base " +
                        "mesh and level count needs " + std::to_string(layout.width()) + "x" +
                        std::to_string(layout.height()));
  }
  return &layout;
}

void KeyGroupGeometry::Positions(std::span<const RigidTransform> transforms,
                                 const GreyPicture& picture, const DisplacementLayout& layout,
                                 const DisplacementRange& range, int level,
                                 std::vector<Eigen::Vector3f>* positions) {
  PoseVertices(motion_, transforms, base_.positions, &posed_);
  ComputeVertexNormals(posed_, base_.triangles, &normals_);
  EvaluateSampleFrames(subdivision_, level, posed_, normals_, &origins_, &directions_);
  const std::size_t count = subdivision_.sample_count(level);
  layout.Unpack(picture, range, count, &displacements_);
  positions->resize(count);
  for (std::size_t s = 0; s < count; ++s) {
    (*positions)[s] = origins_[s] + displacements_[s] * directions_[s];
  }
}

}  // namespace meshvid
