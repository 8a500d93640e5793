#pragma once
// SO(3) and its Lie algebra so(3) ≅ ℝ³ (hat/vee), with the maps the schemes
// need: exp, log, Cayley, Ad, and the trivialised derivatives of exp and cay.
//
// Conventions (docs/conventions.md §3): "body" trivialisation means
// the derivative of R(t) = R0 · map(ξ(t)) expressed as a body velocity,
//     Ω = dmap_body(ξ) ξ̇,   i.e.  d/dt map(ξ) = map(ξ) (dmap_body(ξ) ξ̇)^ ,
// and "space" means the derivative of R(t) = map(ξ(t)) · R0 as a spatial one,
//     ω = dmap_space(ξ) ξ̇,  i.e.  d/dt map(ξ) = (dmap_space(ξ) ξ̇)^ map(ξ).
// dexp_body is the "right Jacobian" of robotics texts, dexp_space the "left".
// References: Iserles, Munthe-Kaas, Nørsett & Zanna, Acta Numerica 9 (2000),
// §2–3 and Appendix; Hairer, Lubich & Wanner, GNI (2006), §III.4 and §IV.8;
// the formulas are collected in docs/math.md §1.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "lie/quaternion.hpp"

namespace lgi::lie {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// v̂ w = v × w.
inline Mat3 hat(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return m;
}

/// Inverse of hat on skew matrices; for a general matrix returns the vee of
/// its skew-symmetric part.
inline Vec3 vee(const Mat3& m) {
  return Vec3(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1)) * 0.5;
}

namespace detail {
// Below these angles the closed forms are replaced by Taylor series whose
// first neglected term is below 1e-17 relative (see the comment at each use).
inline constexpr double series_angle = 1e-4;
inline constexpr double series_angle_wide = 1e-2;
}  // namespace detail

/// Rodrigues: exp(ξ̂) = I + a ξ̂ + b ξ̂², a = sinθ/θ, b = (1 − cosθ)/θ².
/// b is evaluated as 2 sin²(θ/2)/θ², which has no cancellation.
inline Mat3 exp_so3(const Vec3& xi) {
  const double theta2 = xi.squaredNorm();
  const double theta = std::sqrt(theta2);
  double a, b;
  if (theta < detail::series_angle) {  // next terms θ⁶/5040, θ⁶/40320 < 1e-27
    a = 1.0 - theta2 / 6.0 + theta2 * theta2 / 120.0;
    b = 0.5 - theta2 / 24.0 + theta2 * theta2 / 720.0;
  } else {
    a = std::sin(theta) / theta;
    const double s = std::sin(0.5 * theta) / theta;
    b = 2.0 * s * s;
  }
  const Mat3 X = hat(xi);
  return Mat3::Identity() + a * X + b * X * X;
}

/// log: SO(3) → so(3), returning ξ with |ξ| ∈ [0, π]. Goes through the unit
/// quaternion (Shepperd), which keeps round-off accuracy as θ → π where
/// the arccos-of-trace formula loses half the digits.
inline Vec3 log_so3(const Mat3& R) { return quat_log(quat_from_matrix(R)); }

/// Cayley map: cay(ξ) = (I − ξ̂/2)⁻¹(I + ξ̂/2) = I + 4/(4 + θ²)(ξ̂ + ξ̂²/2).
/// Its rotation angle is 2 atan(θ/2) < π.
inline Mat3 cay(const Vec3& xi) {
  const Mat3 X = hat(xi);
  return Mat3::Identity() + (4.0 / (4.0 + xi.squaredNorm())) * (X + 0.5 * X * X);
}

/// Inverse Cayley map, defined for rotation angles < π: from the quaternion
/// (w, v) of R with w > 0, ξ = 2 v / w (since cay(ξ) ↔ (2, ξ)/√(4 + θ²)).
/// Returns false where R rotates by π (w = 0), where cay⁻¹ does not exist.
inline bool cay_inv(const Mat3& R, Vec3& xi) {
  const Eigen::Quaterniond q = quat_from_matrix(R);
  if (!(q.w() > 0.0)) return false;
  xi = 2.0 * q.vec() / q.w();
  return true;
}

/// Group operations on SO(3). Ad_R acts on so(3) ≅ ℝ³ as R itself:
/// (R ξ̂ Rᵀ)ˇ = R ξ.
inline Mat3 compose(const Mat3& A, const Mat3& B) { return A * B; }
inline Mat3 inverse(const Mat3& R) { return R.transpose(); }
inline Vec3 Ad(const Mat3& R, const Vec3& xi) { return R * xi; }
/// ad_ξ η = [ξ, η] = ξ × η.
inline Vec3 ad(const Vec3& xi, const Vec3& eta) { return xi.cross(eta); }

namespace detail {
/// (1 − cosθ)/θ² and (θ − sinθ)/θ³, the coefficients of dexp.
inline void dexp_coefficients(double theta2, double& a, double& b) {
  const double theta = std::sqrt(theta2);
  if (theta < series_angle_wide) {  // next terms θ⁶/40320 and θ⁶/362880 < 1e-16·θ⁰
    a = 0.5 - theta2 / 24.0 + theta2 * theta2 / 720.0;
    b = 1.0 / 6.0 - theta2 / 120.0 + theta2 * theta2 / 5040.0;
  } else {
    const double s = std::sin(0.5 * theta) / theta;
    a = 2.0 * s * s;
    b = (theta - std::sin(theta)) / (theta2 * theta);
  }
}
/// c(θ) = (1 − (θ/2) cot(θ/2))/θ² = 1/12 + θ²/720 + θ⁴/30240 + …, the
/// coefficient of ξ̂² in dexp⁻¹ (docs/math.md §1; singular at θ = 2π).
inline double dexpinv_coefficient(double theta2) {
  const double theta = std::sqrt(theta2);
  if (theta < series_angle_wide) {  // next term θ⁶/1209600 < 1e-18
    return 1.0 / 12.0 + theta2 / 720.0 + theta2 * theta2 / 30240.0;
  }
  const double half = 0.5 * theta;
  return (1.0 - half * std::cos(half) / std::sin(half)) / theta2;
}
}  // namespace detail

/// dexp in body trivialisation: d/dt exp(ξ) = exp(ξ) (dexp_body(ξ) ξ̇)^,
/// dexp_body(ξ) = I − (1 − cosθ)/θ² ξ̂ + (θ − sinθ)/θ³ ξ̂².
inline Mat3 dexp_body(const Vec3& xi) {
  double a, b;
  detail::dexp_coefficients(xi.squaredNorm(), a, b);
  const Mat3 X = hat(xi);
  return Mat3::Identity() - a * X + b * X * X;
}
/// dexp in space trivialisation: d/dt exp(ξ) = (dexp_space(ξ) ξ̇)^ exp(ξ),
/// dexp_space(ξ) = dexp_body(−ξ) = I + (1 − cosθ)/θ² ξ̂ + (θ − sinθ)/θ³ ξ̂².
inline Mat3 dexp_space(const Vec3& xi) { return dexp_body(-xi); }

/// Inverse of dexp_body, applied to a vector without forming a matrix:
/// ξ̇ = Ω + ½ ξ × Ω + c(θ) ξ × (ξ × Ω)  (docs/math.md §1 ✓; Iserles et al. 2000,
/// eq. (2.46) written in body form). Valid for |ξ| < 2π.
inline Vec3 dexpinv_body(const Vec3& xi, const Vec3& omega) {
  const Vec3 xo = xi.cross(omega);
  return omega + 0.5 * xo + detail::dexpinv_coefficient(xi.squaredNorm()) * xi.cross(xo);
}
/// Inverse of dexp_space: ξ̇ = ω − ½ ξ × ω + c(θ) ξ × (ξ × ω).
inline Vec3 dexpinv_space(const Vec3& xi, const Vec3& omega) { return dexpinv_body(-xi, omega); }
/// Matrix forms of the inverses.
inline Mat3 dexpinv_body_matrix(const Vec3& xi) {
  const Mat3 X = hat(xi);
  return Mat3::Identity() + 0.5 * X + detail::dexpinv_coefficient(xi.squaredNorm()) * X * X;
}
inline Mat3 dexpinv_space_matrix(const Vec3& xi) { return dexpinv_body_matrix(-xi); }

/// dcay in body trivialisation: d/dt cay(ξ) = cay(ξ) (dcay_body(ξ) ξ̇)^,
/// dcay_body(ξ) = 4/(4 + θ²) (I − ½ ξ̂).
inline Mat3 dcay_body(const Vec3& xi) {
  return (4.0 / (4.0 + xi.squaredNorm())) * (Mat3::Identity() - 0.5 * hat(xi));
}
/// Its inverse, polynomial (docs/math.md §1 ✓): ξ̇ = Ω + ½ ξ × Ω + ¼ (ξ·Ω) ξ.
inline Vec3 dcayinv_body(const Vec3& xi, const Vec3& omega) {
  return omega + 0.5 * xi.cross(omega) + 0.25 * xi.dot(omega) * xi;
}
inline Mat3 dcayinv_body_matrix(const Vec3& xi) {
  return Mat3::Identity() + 0.5 * hat(xi) + 0.25 * xi * xi.transpose();
}
/// Space trivialisation of the Cayley derivatives: the ½ term changes sign.
inline Mat3 dcay_space(const Vec3& xi) { return dcay_body(-xi); }
inline Vec3 dcayinv_space(const Vec3& xi, const Vec3& omega) { return dcayinv_body(-xi, omega); }

/// Geodesic distance |log(Aᵀ B)|, the attitude error of docs/conventions.md §7.
inline double geodesic_distance(const Mat3& A, const Mat3& B) {
  return log_so3(A.transpose() * B).norm();
}

/// |RᵀR − I| (Frobenius): how far a matrix has left SO(3).
inline double orthogonality_error(const Mat3& R) {
  return (R.transpose() * R - Mat3::Identity()).norm();
}

}  // namespace lgi::lie
