#pragma once
// The hook for any other torque in C++ (and for bindings): a callable
// f(t, R, Π, Ω) → body torque, stored by value (no std::function, so the stage
// loop stays free of indirect calls). It has no potential and no closed-form
// derivatives: Jacobians by central differences, step ε^(1/3) scaled (error
// O(ε^(2/3)) ≈ 1e-11 relative, ample for a Newton matrix). Not a scene term:
// build RigidBody<CallableTorque<F>> in code (tests/test_model_jacobian.cpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include "integrators/system/terms/torque_term.hpp"
#include "lie/so3.hpp"

namespace lgi::system {

template <class F>
struct CallableTorque {
  F f;
  static constexpr TermTraits traits{
      .time_dependent = true, .momentum_dependent = true, .may_be_conservative = false, .linear_in_attitude = false};

  Vec3 torque(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const { return f(t, R, Pi, Omega); }
  Vec3 potential_torque(const Mat3& /*R*/) const { return Vec3::Zero(); }
  double potential(const Mat3& /*R*/) const { return 0.0; }
  bool is_conservative() const { return false; }

  /// Perturbs R → R exp(±δ e_j).
  Mat3 torque_jacobian_attitude(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    const double d = std::cbrt(std::numeric_limits<double>::epsilon());
    Mat3 out;
    for (int j = 0; j < 3; ++j) {
      const Vec3 e = d * Vec3::Unit(j);
      out.col(j) = (f(t, Mat3(R * lie::exp_so3(e)), Pi, Omega) - f(t, Mat3(R * lie::exp_so3(-e)), Pi, Omega)) / (2.0 * d);
    }
    return out;
  }
  /// Central differences in Π with Ω = J⁻¹Π moving along.
  Mat3 torque_jacobian_momentum(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t, const Mat3& J_inv) const {
    const double d = std::cbrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, Pi.norm());
    Mat3 out;
    for (int j = 0; j < 3; ++j) {
      const Vec3 e = d * Vec3::Unit(j);
      const Vec3 de = J_inv * e;
      out.col(j) = (f(t, R, Vec3(Pi + e), Vec3(Omega + de)) - f(t, R, Vec3(Pi - e), Vec3(Omega - de))) / (2.0 * d);
    }
    return out;
  }
};
template <class F>
CallableTorque(F) -> CallableTorque<F>;

}  // namespace lgi::system
