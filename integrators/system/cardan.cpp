// The Cardan top's closed forms (the field's, templated on the scalar, in
// integrators/system/cardan_field.hpp); derivation in docs/cardan.md §2–§4,
// checked against automatic differentiation of the rotation matrices in
// tests/test_cardan_model.cpp.
#include "integrators/system/cardan.hpp"

#include <cmath>

#include "integrators/system/cardan_field.hpp"

namespace lgi::system {
namespace {
using cardan_detail::rot_x;
using cardan_detail::rot_y;
using cardan_detail::rot_z;
}  // namespace

Mat3 CardanTop::pedestal() const { return rot_y(suspension.tilt); }

Mat3 CardanTop::attitude(const Vec3& q) const { return pedestal() * rot_z(q[0]) * rot_x(q[1]) * rot_z(q[2]); }

Mat3 CardanTop::body_rate_matrix(const Vec3& q) { return cardan_detail::body_rate_matrix(q); }

Mat3 CardanTop::mass_matrix(const Vec3& q) const { return cardan_detail::mass_matrix(*this, q); }

std::array<Mat3, 3> CardanTop::mass_matrix_derivatives(const Vec3& q) const {
  return cardan_detail::mass_matrix_derivatives(*this, q);
}

double CardanTop::potential(const Vec3& q) const {
  const Vec3 gamma = pedestal().transpose() * Vec3::UnitZ();
  const SuspensionParameters& s = suspension;
  const Vec3 inner = rot_x(q[1]) * (rot_z(q[2]) * (mass * chi) + s.inner_mass * s.inner_center);
  return g * gamma.dot(rot_z(q[0]) * (inner + s.outer_mass * s.outer_center));
}

Vec3 CardanTop::potential_gradient(const Vec3& q) const { return cardan_detail::potential_gradient(*this, q); }

Vec3 CardanTop::velocity(const TorusState& x) const { return mass_matrix(x.q).inverse() * x.p; }

double CardanTop::energy(const TorusState& x) const { return 0.5 * x.p.dot(velocity(x)) + potential(x.q); }

Vec6 CardanTop::energy_gradient(const TorusState& x) const { return cardan_detail::energy_gradient(*this, x.q, x.p); }

Vec6 CardanTop::field(const TorusState& x) const { return cardan_detail::field(*this, x.q, x.p); }

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
