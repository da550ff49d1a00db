#include "codec/enc/rigid_step.h"

#include <Eigen/Geometry>

namespace meshvid {
namespace {

/// Weight of the point-to-point term beside the point-to-plane one.
constexpr double kPointWeight = 0.05;
/// Damping of a rigid step, relative to the block's mean diagonal.
constexpr double kDamping = 1e-3;

}  // namespace

Eigen::Matrix<double, 3, 6> PointJacobian(const Eigen::Vector3d& q) {
  Eigen::Matrix3d skew;
  skew << 0, -q.z(), q.y(), q.z(), 0, -q.x(), -q.y(), q.x(), 0;
  Eigen::Matrix<double, 3, 6> j;
  j << -skew, Eigen::Matrix3d::Identity();
  return j;
}

void AddCorrespondence(const Eigen::Vector3d& q, const Eigen::Vector3d& n,
                       const Eigen::Vector3d& r, Matrix6d* a, Vector6d* b, double weight) {
  Vector6d j;
  j << q.cross(n), n;
  *a += weight * j * j.transpose();
  *b += weight * j * n.dot(r);
  const Eigen::Matrix<double, 3, 6> jp = PointJacobian(q);
  *a += weight * kPointWeight * jp.transpose() * jp;
  *b += weight * kPointWeight * jp.transpose() * r;
}

void DampRigidBlock(Matrix6d* a) {
  a->diagonal().array() += kDamping * a->trace() / 6.0 + 1e-12;
}

RigidTransform ApplyIncrement(const RigidTransform& transform, const Vector6d& x,
                              const Eigen::Vector3d& centre) {
  const Eigen::Vector3d w = x.head<3>(), d = x.tail<3>();
  const double angle = w.norm();
  const Eigen::Quaterniond step = angle > 0
                                      ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle))
                                      : Eigen::Quaterniond::Identity();
  RigidTransform result;
  result.rotation = (step.cast<float>() * transform.rotation).normalized();
  result.translation =
      (step * (transform.translation.cast<double>() - centre) + centre + d).cast<float>();
  return result;
}

}  // namespace meshvid
