#pragma once
// Unit quaternions for SO(3), scalar first: q = (w, x, y, z), body → space,
// v_space = q v q*. q and −q are the same attitude.
// Eigen::Quaterniond(w, x, y, z) takes this order, but its coeffs() stores
// (x, y, z, w): use to_wxyz() for anything written out.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>

namespace lgi::lie {

/// Shepperd's method (J. Guidance Control 1 (1978) 223): choose the largest
/// of 4w², 4x², 4y², 4z² (from the trace and the diagonal) to divide by, so
/// no step loses precision. Returns the quaternion with w ≥ 0.
inline Eigen::Quaterniond quat_from_matrix(const Eigen::Matrix3d& R) {
  const double t = R.trace();
  const double d0 = R(0, 0), d1 = R(1, 1), d2 = R(2, 2);
  double w, x, y, z;
  if (t >= d0 && t >= d1 && t >= d2) {
    const double r = std::sqrt(1.0 + t);  // 2|w|
    const double s = 0.5 / r;
    w = 0.5 * r;
    x = (R(2, 1) - R(1, 2)) * s;
    y = (R(0, 2) - R(2, 0)) * s;
    z = (R(1, 0) - R(0, 1)) * s;
  } else if (d0 >= d1 && d0 >= d2) {
    const double r = std::sqrt(1.0 + d0 - d1 - d2);  // 2|x|
    const double s = 0.5 / r;
    x = 0.5 * r;
    w = (R(2, 1) - R(1, 2)) * s;
    y = (R(0, 1) + R(1, 0)) * s;
    z = (R(0, 2) + R(2, 0)) * s;
  } else if (d1 >= d2) {
    const double r = std::sqrt(1.0 - d0 + d1 - d2);  // 2|y|
    const double s = 0.5 / r;
    y = 0.5 * r;
    w = (R(0, 2) - R(2, 0)) * s;
    x = (R(0, 1) + R(1, 0)) * s;
    z = (R(1, 2) + R(2, 1)) * s;
  } else {
    const double r = std::sqrt(1.0 - d0 - d1 + d2);  // 2|z|
    const double s = 0.5 / r;
    z = 0.5 * r;
    w = (R(1, 0) - R(0, 1)) * s;
    x = (R(0, 2) + R(2, 0)) * s;
    y = (R(1, 2) + R(2, 1)) * s;
  }
  if (w < 0.0) { w = -w; x = -x; y = -y; z = -z; }
  return Eigen::Quaterniond(w, x, y, z);
}

/// The entries of R(q), row-major, for a unit quaternion (w, x, y, z) of any
/// arithmetic type T (a double, or the SIMD lanes of integrators/ensemble/,
/// which must round as the scalar code does): R = I + 2w x̂ + 2x̂², x = (x, y, z).
/// No normalisation: a non-unit q gives a non-orthogonal matrix, which the
/// orthogonality observable then shows.
template <class T>
inline void rotation_entries(const T& w, const T& x, const T& y, const T& z, T (&R)[9]) {
  R[0] = 1.0 - 2.0 * (y * y + z * z), R[1] = 2.0 * (x * y - w * z), R[2] = 2.0 * (x * z + w * y);
  R[3] = 2.0 * (x * y + w * z), R[4] = 1.0 - 2.0 * (x * x + z * z), R[5] = 2.0 * (y * z - w * x);
  R[6] = 2.0 * (x * z - w * y), R[7] = 2.0 * (y * z + w * x), R[8] = 1.0 - 2.0 * (x * x + y * y);
}

/// R(q) for a unit quaternion (rotation_entries).
inline Eigen::Matrix3d matrix_from_quat(const Eigen::Quaterniond& q) {
  double e[9];
  rotation_entries(q.w(), q.x(), q.y(), q.z(), e);
  Eigen::Matrix3d R;
  R << e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7], e[8];
  return R;
}

/// exp on the unit quaternions: (cos(θ/2), sin(θ/2) ξ/θ).
inline Eigen::Quaterniond quat_exp(const Eigen::Vector3d& xi) {
  const double theta = xi.norm();
  const double half = 0.5 * theta;
  // sin(θ/2)/θ = ½ (1 − θ²/24 + θ⁴/1920) for small θ; next term < 1e-26.
  const double s = theta < 1e-4 ? 0.5 * (1.0 - theta * theta / 24.0 + theta * theta * theta * theta / 1920.0)
                                : std::sin(half) / theta;
  return Eigen::Quaterniond(std::cos(half), s * xi.x(), s * xi.y(), s * xi.z());
}

/// log on the unit quaternions, returning ξ with |ξ| ∈ [0, π] (q and −q give
/// the same ξ): ξ = 2 atan2(|v|, |w|) v/|v| · sign(w).
inline Eigen::Vector3d quat_log(const Eigen::Quaterniond& q_in) {
  Eigen::Vector3d v = q_in.vec();
  double w = q_in.w();
  if (w < 0.0) { w = -w; v = -v; }
  const double n = v.norm();
  double scale;  // θ/|v| = 2 atan2(n, w)/n
  if (n < 1e-8 * w) {
    // atan(u)/u = 1 − u²/3 + …, u = n/w < 1e-8: the u² term is below 1e-16.
    scale = 2.0 / w * (1.0 - (n * n) / (3.0 * w * w));
  } else {
    scale = 2.0 * std::atan2(n, w) / n;
  }
  return scale * v;
}

/// (w, x, y, z) for output: never write Eigen's coeffs().
inline std::array<double, 4> to_wxyz(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }

/// The attitude distance 2 atan2(|vec(a* b)|, |w(a* b)|), which treats q and −q alike.
inline double quat_distance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const Eigen::Quaterniond d = a.conjugate() * b;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

}  // namespace lgi::lie
