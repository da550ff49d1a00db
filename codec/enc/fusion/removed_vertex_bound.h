// A decimation module for OpenMesh's decimater: the bound on how far the surface may move from
// the vertices it removes (the decimation's max_error).
#ifndef MESHVID_CODEC_ENC_FUSION_REMOVED_VERTEX_BOUND_H_
#define MESHVID_CODEC_ENC_FUSION_REMOVED_VERTEX_BOUND_H_

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include "codec/common/triangle_distance.h"

namespace meshvid {

/// Refuses a collapse that would leave a removed vertex farther than max_distance from the
/// surface. Each face keeps the input positions of the removed vertices nearest to it; a
/// collapse of v0 into v1 is legal when every position kept by v0's faces, and v0's own, lies
/// within the distance of one of the faces around v1 after it. The same rule as OpenMesh's
/// ModHausdorffT, made cheap: a position within the distance of a corner of those faces passes
/// without a triangle test; after a collapse only the positions of the faces that moved or went
/// are handed on (the others' faces did not move), each to its nearest face around v1, skipping
/// the faces whose bounding sphere is farther than the nearest found so far.
template <class MeshT>
class ModRemovedVertexBoundT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModRemovedVertexBoundT, MeshT, RemovedVertexBound);

  explicit ModRemovedVertexBoundT(MeshT& mesh) : Base(mesh, /*is_binary=*/true) {
    Base::mesh().add_property(removed_);
  }
  ~ModRemovedVertexBoundT() override { Base::mesh().remove_property(removed_); }

  /// The farthest a removed vertex may lie from the decimated surface.
  void set_max_distance(float distance) { max_squared_ = distance * distance; }

  void initialize() override {
    MeshT& m = Base::mesh();
    for (auto f : m.faces()) m.property(removed_, f).clear();
  }

  float collapse_priority(const CollapseInfo& ci) override {
    MeshT& m = Base::mesh();
    corners_.clear();
    positions_.clear();
    const Eigen::Vector3f p1 = ToEigen(ci.p1);
    for (auto h : m.voh_range(ci.v0)) {
      const auto face = m.face_handle(h);
      if (!face.is_valid()) continue;
      const std::vector<Eigen::Vector3f>& kept = m.property(removed_, face);
      positions_.insert(positions_.end(), kept.begin(), kept.end());
      if (face == ci.fl || face == ci.fr) continue;
      corners_.push_back(p1);
      corners_.push_back(ToEigen(m.point(m.to_vertex_handle(h))));
      corners_.push_back(ToEigen(m.point(m.to_vertex_handle(m.next_halfedge_handle(h)))));
    }
    if (corners_.empty()) return Base::ILLEGAL_COLLAPSE;
    positions_.push_back(ToEigen(ci.p0));
    for (const Eigen::Vector3f& q : positions_) {
      if (!NearSomeFace(q)) return Base::ILLEGAL_COLLAPSE;
    }
    return Base::LEGAL_COLLAPSE;
  }

  void preprocess_collapse(const CollapseInfo& ci) override {
    // The faces that move: v0's, but for the two the collapse removes.
    moved_.clear();
    for (auto face : Base::mesh().vf_range(ci.v0)) {
      if (face != ci.fl && face != ci.fr) moved_.push_back(face);
    }
  }

  void postprocess_collapse(const CollapseInfo& ci) override {
    MeshT& m = Base::mesh();
    positions_.clear();
    faces_.clear();
    corners_.clear();
    auto take = [&](typename MeshT::FaceHandle face) {
      std::vector<Eigen::Vector3f>& kept = m.property(removed_, face);
      positions_.insert(positions_.end(), kept.begin(), kept.end());
      kept.clear();
    };
    // Positions kept by faces that did not move stay with them (still within the distance);
    // those of the faces that moved or went, and v0's, go to their nearest face around v1.
    for (auto face : moved_) take(face);
    if (ci.fl.is_valid()) take(ci.fl);
    if (ci.fr.is_valid()) take(ci.fr);
    for (auto face : m.vf_range(ci.v1)) {
      faces_.push_back(face);
      for (auto v : m.fv_range(face)) corners_.push_back(ToEigen(m.point(v)));
    }
    positions_.push_back(ToEigen(ci.p0));
    if (faces_.empty()) return;
    // Each face's bounding sphere: no point of the face is nearer to q than |q - centre| - radius.
    centres_.resize(faces_.size());
    radii_.resize(faces_.size());
    for (std::size_t k = 0; k < faces_.size(); ++k) {
      const Eigen::Vector3f* c = &corners_[3 * k];
      centres_[k] = (c[0] + c[1] + c[2]) / 3.0f;
      radii_[k] = std::sqrt(std::max({(c[0] - centres_[k]).squaredNorm(),
                                      (c[1] - centres_[k]).squaredNorm(),
                                      (c[2] - centres_[k]).squaredNorm()}));
    }
    lower_.resize(faces_.size());
    for (const Eigen::Vector3f& q : positions_) {
      // The face with the nearest sphere first: it is most often the nearest face, and its
      // distance rules out most others by their spheres.
      std::size_t nearest = 0;
      for (std::size_t k = 0; k < faces_.size(); ++k) {
        lower_[k] = (q - centres_[k]).norm() - radii_[k];
        if (lower_[k] < lower_[nearest]) nearest = k;
      }
      const Eigen::Vector3f* c = &corners_[3 * nearest];
      float best = SquaredDistanceToTriangle(q, c[0], c[1], c[2]);
      for (std::size_t k = 0; k < faces_.size(); ++k) {
        if (k == nearest || (lower_[k] > 0 && lower_[k] * lower_[k] > best)) continue;
        c = &corners_[3 * k];
        const float squared = SquaredDistanceToTriangle(q, c[0], c[1], c[2]);
        if (squared < best || (squared == best && k < nearest)) {  // ties: the first face
          best = squared;
          nearest = k;
        }
      }
      m.property(removed_, faces_[nearest]).push_back(q);
    }
  }

 private:
  template <class Point>
  static Eigen::Vector3f ToEigen(const Point& p) {
    return Eigen::Vector3f(p[0], p[1], p[2]);
  }

  // True if q lies within the distance of one of the triangles in corners_.
  bool NearSomeFace(const Eigen::Vector3f& q) const {
    // A triangle is at least as near as each of its corners.
    for (const Eigen::Vector3f& corner : corners_) {
      if ((q - corner).squaredNorm() <= max_squared_) return true;
    }
    for (std::size_t k = 0; k < corners_.size(); k += 3) {
      if (SquaredDistanceToTriangle(q, corners_[k], corners_[k + 1], corners_[k + 2]) <=
          max_squared_) {
        return true;
      }
    }
    return false;
  }

  float max_squared_ = std::numeric_limits<float>::max();
  OpenMesh::FPropHandleT<std::vector<Eigen::Vector3f>> removed_;
  // Scratch space, kept between calls to save allocations.
  std::vector<Eigen::Vector3f> positions_, corners_, centres_;
  std::vector<float> radii_, lower_;
  std::vector<typename MeshT::FaceHandle> faces_, moved_;
};

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_FUSION_REMOVED_VERTEX_BOUND_H_
