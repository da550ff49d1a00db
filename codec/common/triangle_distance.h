// The point of a triangle closest to a given point, in float or double: the exact
// point-to-surface distances of `meshvid eval` (double) and the decimation's bound on how far
// the removed vertices lie from the decimated surface (float).
#ifndef MESHVID_CODEC_COMMON_TRIANGLE_DISTANCE_H_
#define MESHVID_CODEC_COMMON_TRIANGLE_DISTANCE_H_

#include <Eigen/Core>

namespace meshvid {

/// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection 5.1.5).
/// A degenerate triangle gives the closest point of its edges.
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 1> ClosestPointOnTriangle(const Eigen::Matrix<Scalar, 3, 1>& p,
                                                   const Eigen::Matrix<Scalar, 3, 1>& a,
                                                   const Eigen::Matrix<Scalar, 3, 1>& b,
                                                   const Eigen::Matrix<Scalar, 3, 1>& c) {
  using Vector = Eigen::Matrix<Scalar, 3, 1>;
  const Scalar zero(0);
  const Vector ab = b - a, ac = c - a, ap = p - a;
  const Scalar d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= zero && d2 <= zero) return a;  // vertex region a
  const Vector bp = p - b;
  const Scalar d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= zero && d4 <= d3) return b;  // vertex region b
  const Scalar vc = d1 * d4 - d3 * d2;
  if (vc <= zero && d1 >= zero && d3 <= zero) return a + (d1 / (d1 - d3)) * ab;  // edge ab
  const Vector cp = p - c;
  const Scalar d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= zero && d5 <= d6) return c;  // vertex region c
  const Scalar vb = d5 * d2 - d1 * d6;
  if (vb <= zero && d2 >= zero && d6 <= zero) return a + (d2 / (d2 - d6)) * ac;  // edge ac
  const Scalar va = d3 * d6 - d5 * d4;
  if (va <= zero && (d4 - d3) >= zero && (d5 - d6) >= zero) {  // edge bc
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const Scalar denom = va + vb + vc;
  if (!(denom > zero)) return a;  // degenerate triangle: any vertex is as good (edges handled)
  const Scalar v = vb / denom, w = vc / denom;
  return a + v * ab + w * ac;  // interior
}

/// The squared distance from p to triangle (a, b, c).
template <typename Scalar>
Scalar SquaredDistanceToTriangle(const Eigen::Matrix<Scalar, 3, 1>& p,
                                 const Eigen::Matrix<Scalar, 3, 1>& a,
                                 const Eigen::Matrix<Scalar, 3, 1>& b,
                                 const Eigen::Matrix<Scalar, 3, 1>& c) {
  return (ClosestPointOnTriangle(p, a, b, c) - p).squaredNorm();
}

/// The barycentric weights (of a, b, c) of point p of triangle (a, b, c)'s plane; (1, 0, 0)
/// for a degenerate triangle.
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 1> BarycentricWeights(const Eigen::Matrix<Scalar, 3, 1>& p,
                                               const Eigen::Matrix<Scalar, 3, 1>& a,
                                               const Eigen::Matrix<Scalar, 3, 1>& b,
                                               const Eigen::Matrix<Scalar, 3, 1>& c) {
  using Vector = Eigen::Matrix<Scalar, 3, 1>;
  const Vector e0 = b - a, e1 = c - a, e2 = p - a;
  const Scalar d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const Scalar d20 = e2.dot(e0), d21 = e2.dot(e1);
  const Scalar denominator = d00 * d11 - d01 * d01;
  if (!(denominator > Scalar(0))) return Vector(1, 0, 0);
  const Scalar wb = (d11 * d20 - d01 * d21) / denominator;
  const Scalar wc = (d00 * d21 - d01 * d20) / denominator;
  return Vector(1 - wb - wc, wb, wc);
}

}  // namespace meshvid

#endif  // MESHVID_CODEC_COMMON_TRIANGLE_DISTANCE_H_
