// The pieces of a Gauss-Newton step of rigid transforms (docs/encoder-method.md eq. 5) shared by
// the segmentation and the patch tracking: one correspondence's terms, the damping, and the update
// of a transform by a solved increment. An increment x = (w, d) about a centre c moves a posed
// point p to p + w x (p - c) + d.
#ifndef MESHVID_CODEC_ENC_RIGID_STEP_H_
#define MESHVID_CODEC_ENC_RIGID_STEP_H_

#include <Eigen/Core>

#include "codec/common/motion.h"

namespace meshvid {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

/// The derivative of a posed point q (relative to the centre) by the increment (w, d):
/// [-[q]x, I].
Eigen::Matrix<double, 3, 6> PointJacobian(const Eigen::Vector3d& q);

/// Adds one correspondence to the normal equations (a, b): the point-to-plane distance of
/// the posed point to the data's tangent plane (normal n; Chen & Medioni, whose normal
/// shooting gives the correspondences), plus a small point-to-point term that fixes the
/// directions a plane leaves free. q: the posed point relative to the centre; r: the posed
/// point minus its correspondence; `weight` scales both terms (a robust weight).
void AddCorrespondence(const Eigen::Vector3d& q, const Eigen::Vector3d& n,
                       const Eigen::Vector3d& r, Matrix6d* a, Vector6d* b,
                       double weight = 1.0);

/// Levenberg-Marquardt damping of one 6x6 block, relative to its mean diagonal: few or
/// nearly collinear points leave directions almost free; damping keeps the step there small
/// instead of arbitrary.
void DampRigidBlock(Matrix6d* a);

/// `transform` followed by the increment x = (w, d) about `centre`:
/// y -> R(w) (T y - centre) + centre + d.
RigidTransform ApplyIncrement(const RigidTransform& transform, const Vector6d& x,
                              const Eigen::Vector3d& centre);

}  // namespace meshvid

#endif  // MESHVID_CODEC_ENC_RIGID_STEP_H_
