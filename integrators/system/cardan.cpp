// The Cardan top's closed forms; derivation in docs/cardan.md §2–§4,
// checked against automatic differentiation of the rotation matrices in
// tests/test_cardan_model.cpp.
#include "integrators/system/cardan.hpp"

#include <cmath>

namespace lgi::system {
namespace {

Mat3 rot_x(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Mat3 m;
  m << 1, 0, 0, 0, c, -s, 0, s, c;
  return m;
}
Mat3 rot_y(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Mat3 m;
  m << c, 0, s, 0, 1, 0, -s, 0, c;
  return m;
}
Mat3 rot_z(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Mat3 m;
  m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}

/// F(q) of eq. (3): the inner ring's angular velocity in its frame is F q̇.
Mat3 inner_rate_matrix(double q2) {
  Mat3 F;
  F << 0, 1, 0, std::sin(q2), 0, 0, std::cos(q2), 0, 0;
  return F;
}

}  // namespace

Mat3 CardanTop::pedestal() const { return rot_y(suspension.tilt); }

Mat3 CardanTop::attitude(const Vec3& q) const { return pedestal() * rot_z(q[0]) * rot_x(q[1]) * rot_z(q[2]); }

Mat3 CardanTop::body_rate_matrix(const Vec3& q) {
  const double s2 = std::sin(q[1]), c2 = std::cos(q[1]), s3 = std::sin(q[2]), c3 = std::cos(q[2]);
  Mat3 E;
  E << s2 * s3, c3, 0, s2 * c3, -s3, 0, c2, 0, 1;
  return E;
}

Mat3 CardanTop::mass_matrix(const Vec3& q) const {
  const Mat3 E = body_rate_matrix(q);
  const Mat3 F = inner_rate_matrix(q[1]);
  Mat3 M = E.transpose() * J * E + F.transpose() * suspension.inner_inertia.asDiagonal() * F;
  M(0, 0) += suspension.outer_inertia;
  return M;
}

std::array<Mat3, 3> CardanTop::mass_matrix_derivatives(const Vec3& q) const {
  const double s2 = std::sin(q[1]), c2 = std::cos(q[1]), s3 = std::sin(q[2]), c3 = std::cos(q[2]);
  const Mat3 E = body_rate_matrix(q);
  Mat3 E2, E3, F2;  // ∂E/∂q2, ∂E/∂q3, ∂F/∂q2 (eq. (6))
  E2 << c2 * s3, 0, 0, c2 * c3, 0, 0, -s2, 0, 0;
  E3 << s2 * c3, -s3, 0, -s2 * s3, -c3, 0, 0, 0, 0;
  F2 << 0, 0, 0, c2, 0, 0, -s2, 0, 0;
  const Mat3 F = inner_rate_matrix(q[1]);
  const Mat3 K = suspension.inner_inertia.asDiagonal();
  const Mat3 JE = J * E;
  std::array<Mat3, 3> d;
  d[0].setZero();
  d[1] = E2.transpose() * JE + JE.transpose() * E2 + F2.transpose() * K * F + F.transpose() * K * F2;
  d[2] = E3.transpose() * JE + JE.transpose() * E3;
  return d;
}

double CardanTop::potential(const Vec3& q) const {
  const Vec3 gamma = pedestal().transpose() * Vec3::UnitZ();
  const SuspensionParameters& s = suspension;
  const Vec3 inner = rot_x(q[1]) * (rot_z(q[2]) * (mass * chi) + s.inner_mass * s.inner_center);
  return g * gamma.dot(rot_z(q[0]) * (inner + s.outer_mass * s.outer_center));
}

Vec3 CardanTop::potential_gradient(const Vec3& q) const {
  // eq. (5'): derivatives of Rz(a) and Rx(a) are Rz(a) ê3 and Rx(a) ê1.
  const Vec3 gamma = pedestal().transpose() * Vec3::UnitZ();
  const SuspensionParameters& s = suspension;
  const Mat3 Z1 = rot_z(q[0]), X2 = rot_x(q[1]), Z3 = rot_z(q[2]);
  const Vec3 u = Z3 * (mass * chi) + s.inner_mass * s.inner_center;
  const Vec3 w = X2 * u + s.outer_mass * s.outer_center;
  return g * Vec3(gamma.dot(Z1 * Vec3::UnitZ().cross(w)), gamma.dot(Z1 * X2 * Vec3::UnitX().cross(u)),
                  gamma.dot(Z1 * X2 * Z3 * Vec3::UnitZ().cross(mass * chi)));
}

Vec3 CardanTop::velocity(const TorusState& x) const { return mass_matrix(x.q).inverse() * x.p; }

double CardanTop::energy(const TorusState& x) const { return 0.5 * x.p.dot(velocity(x)) + potential(x.q); }

Vec6 CardanTop::energy_gradient(const TorusState& x) const {
  const Vec3 v = velocity(x);
  const std::array<Mat3, 3> dM = mass_matrix_derivatives(x.q);
  // ∂/∂q_k (½ pᵀM⁻¹p) = −½ vᵀ (∂M/∂q_k) v.
  const Vec3 dV = potential_gradient(x.q);
  Vec6 grad;
  for (int k = 0; k < 3; ++k) grad[k] = -0.5 * v.dot(dM[static_cast<std::size_t>(k)] * v) + dV[k];
  grad.tail<3>() = v;
  return grad;
}

Vec6 CardanTop::field(const TorusState& x) const {
  const Vec6 grad = energy_gradient(x);
  Vec6 f;
  f << grad.tail<3>(), -grad.head<3>();
  return f;
}

Mat6 CardanTop::field_jacobian(const TorusState& x) const {
  const Vec6 y = stack(x);
  Mat6 jac;
  for (int j = 0; j < 6; ++j) {
    const double d = 1e-6 * std::max(1.0, std::abs(y[j]));
    Vec6 plus = y, minus = y;
    plus[j] += d;
    minus[j] -= d;
    jac.col(j) = (field(unstack(plus)) - field(unstack(minus))) / (2.0 * d);
  }
  return jac;
}

lie::SO3xR3 CardanTop::body_state(const TorusState& x) const {
  return {attitude(x.q), J * (body_rate_matrix(x.q) * velocity(x))};
}

bool CardanTop::outer_angle_cyclic() const {
  if (g == 0.0) return true;
  return suspension.tilt == 0.0;
}

}  // namespace lgi::system
