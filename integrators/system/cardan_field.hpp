#pragma once
// The Cardan top's mass matrix, potential gradient and canonical field
// (docs/cardan.md eqs. (2)–(7); integrators/system/cardan.hpp), templated on
// the scalar type S. CardanTop's members call them with S = double (the
// same operations as always, so results are unchanged bit for bit); the
// tangent flow (integrators/core/torus_tangent_flow.hpp) calls the field
// with S = Dual (integrators/system/dual.hpp), whose ε-part is the exact
// directional derivative Df(x) v. The model's parameters stay double and
// enter as constants.
#include <array>
#include <cmath>

#include <Eigen/LU>

#include "integrators/system/cardan.hpp"

namespace lgi::system::cardan_detail {

template <class S>
using Vec3T = Eigen::Matrix<S, 3, 1>;
template <class S>
using Mat3T = Eigen::Matrix<S, 3, 3>;
template <class S>
using Vec6T = Eigen::Matrix<S, 6, 1>;

template <class S>
Mat3T<S> rot_x(const S& a) {
  using std::cos, std::sin;
  const S c = cos(a), s = sin(a);
  Mat3T<S> m;
  m << 1, 0, 0, 0, c, -s, 0, s, c;
  return m;
}
template <class S>
Mat3T<S> rot_y(const S& a) {
  using std::cos, std::sin;
  const S c = cos(a), s = sin(a);
  Mat3T<S> m;
  m << c, 0, s, 0, 1, 0, -s, 0, c;
  return m;
}
template <class S>
Mat3T<S> rot_z(const S& a) {
  using std::cos, std::sin;
  const S c = cos(a), s = sin(a);
  Mat3T<S> m;
  m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}

/// E(q) of eq. (2): body Ω = E q̇.
template <class S>
Mat3T<S> body_rate_matrix(const Vec3T<S>& q) {
  using std::cos, std::sin;
  const S s2 = sin(q[1]), c2 = cos(q[1]), s3 = sin(q[2]), c3 = cos(q[2]);
  Mat3T<S> E;
  E << s2 * s3, c3, 0, s2 * c3, -s3, 0, c2, 0, 1;
  return E;
}

/// F(q) of eq. (3): the inner ring's angular velocity in its frame is F q̇.
template <class S>
Mat3T<S> inner_rate_matrix(const S& q2) {
  using std::cos, std::sin;
  Mat3T<S> F;
  F << 0, 1, 0, sin(q2), 0, 0, cos(q2), 0, 0;
  return F;
}

/// M(q) of eq. (4).
template <class S>
Mat3T<S> mass_matrix(const CardanTop& top, const Vec3T<S>& q) {
  const Mat3T<S> E = body_rate_matrix(q);
  const Mat3T<S> F = inner_rate_matrix(q[1]);
  const Mat3T<S> J = top.J.cast<S>();
  const Vec3T<S> K = top.suspension.inner_inertia.cast<S>();
  Mat3T<S> M = E.transpose() * J * E + F.transpose() * K.asDiagonal() * F;
  M(0, 0) += S(top.suspension.outer_inertia);
  return M;
}

/// ∂M/∂q_k (k = 0, 1, 2; ∂M/∂q1 = 0), eq. (6).
template <class S>
std::array<Mat3T<S>, 3> mass_matrix_derivatives(const CardanTop& top, const Vec3T<S>& q) {
  using std::cos, std::sin;
  const S s2 = sin(q[1]), c2 = cos(q[1]), s3 = sin(q[2]), c3 = cos(q[2]);
  const Mat3T<S> E = body_rate_matrix(q);
  Mat3T<S> E2, E3, F2;  // ∂E/∂q2, ∂E/∂q3, ∂F/∂q2
  E2 << c2 * s3, 0, 0, c2 * c3, 0, 0, -s2, 0, 0;
  E3 << s2 * c3, -s3, 0, -s2 * s3, -c3, 0, 0, 0, 0;
  F2 << 0, 0, 0, c2, 0, 0, -s2, 0, 0;
  const Mat3T<S> F = inner_rate_matrix(q[1]);
  const Mat3T<S> K = top.suspension.inner_inertia.cast<S>().asDiagonal();
  const Mat3T<S> JE = top.J.cast<S>() * E;
  std::array<Mat3T<S>, 3> d;
  d[0].setZero();
  d[1] = E2.transpose() * JE + JE.transpose() * E2 + F2.transpose() * K * F + F.transpose() * K * F2;
  d[2] = E3.transpose() * JE + JE.transpose() * E3;
  return d;
}

/// ∂V/∂q, eq. (5'): the derivatives of Rz(a) and Rx(a) are Rz(a) ê3 and Rx(a) ê1.
template <class S>
Vec3T<S> potential_gradient(const CardanTop& top, const Vec3T<S>& q) {
  const Vec3T<S> gamma = (top.pedestal().transpose() * Vec3::UnitZ()).cast<S>();
  const SuspensionParameters& s = top.suspension;
  const Mat3T<S> Z1 = rot_z(q[0]), X2 = rot_x(q[1]), Z3 = rot_z(q[2]);
  const Vec3T<S> mchi = (top.mass * top.chi).cast<S>();
  const Vec3T<S> u = Z3 * mchi + (s.inner_mass * s.inner_center).cast<S>();
  const Vec3T<S> w = X2 * u + (s.outer_mass * s.outer_center).cast<S>();
  const Vec3T<S> e1 = Vec3T<S>::UnitX(), e3 = Vec3T<S>::UnitZ();
  return S(top.g) * Vec3T<S>(gamma.dot(Z1 * e3.cross(w)), gamma.dot(Z1 * X2 * e1.cross(u)),
                             gamma.dot(Z1 * X2 * Z3 * e3.cross(mchi)));
}

/// (∂H/∂q, ∂H/∂p) at (q, p); ∂/∂q_k (½ pᵀM⁻¹p) = −½ vᵀ (∂M/∂q_k) v, v = M⁻¹ p.
template <class S>
Vec6T<S> energy_gradient(const CardanTop& top, const Vec3T<S>& q, const Vec3T<S>& p) {
  const Vec3T<S> v = mass_matrix(top, q).inverse() * p;
  const std::array<Mat3T<S>, 3> dM = mass_matrix_derivatives(top, q);
  const Vec3T<S> dV = potential_gradient(top, q);
  Vec6T<S> grad;
  for (int k = 0; k < 3; ++k) grad[k] = S(-0.5) * v.dot(dM[static_cast<std::size_t>(k)] * v) + dV[k];
  grad.template tail<3>() = v;
  return grad;
}

/// The canonical field (q̇, ṗ) = (∂H/∂p, −∂H/∂q), eq. (7).
template <class S>
Vec6T<S> field(const CardanTop& top, const Vec3T<S>& q, const Vec3T<S>& p) {
  const Vec6T<S> grad = energy_gradient(top, q, p);
  Vec6T<S> f;
  f << grad.template tail<3>(), -grad.template head<3>();
  return f;
}

}  // namespace lgi::system::cardan_detail
