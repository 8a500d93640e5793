#pragma once
// The angular-velocity half of every baseline's right-hand side, built on the
// project's rigid-body model (integrators/system), not on a second copy of
// the physics:
//   Ω̇ = J⁻¹ K(R, JΩ, Ω, t),   K = Π × Ω + τ   (model.momentum_rate)
// i.e. Ω̇ = J⁻¹(JΩ × Ω + τ) (Trindade & Sampaio 2001, the first three rows of
// eq. 25 and eq. 26, there written for a heavy top with the parallel-axis
// moments I_i + mL²; docs/conventions.md §4 for the body form).
//
// Its derivatives, for rosenbrock4, come from the model's analytic Jacobians
// (RigidBody::momentum_rate_jacobian, body-side perturbation R → R exp(η̂)):
//   ∂Ω̇/∂η = J⁻¹ ∂K/∂η,   ∂Ω̇/∂Ω = J⁻¹ (∂K/∂Π) J   (Π = JΩ),
// and ∂Ω̇/∂t = J⁻¹ ∂τ/∂t (zero unless a term is time dependent; closed form
// for the harmonic drive, central differences for a generic callable).
// Each chart supplies ∂η/∂(its coordinates); the matrix chart, whose R is
// not constrained to SO(3), uses matrix_torque_differential() below.
#include <cmath>
#include <limits>
#include <tuple>
#include <type_traits>

#include "integrators/system/rigid_body.hpp"

namespace lgi::integrators::baselines {

using lie::Mat3;
using lie::Vec3;
using system::State;

/// Ω̇ = J⁻¹ K(R, JΩ, Ω, t). R is not formed by the caller for a free body
/// (the field does not depend on it): pass any matrix.
template <class Model>
Vec3 omega_rate(const Model& model, const Mat3& R, const Vec3& Omega, double t) {
  const Vec3 Pi = model.inertia.J * Omega;
  return model.inertia.J_inv * model.momentum_rate(R, Pi, Omega, t);
}

/// ∂τ/∂t summed over the terms: 0 for terms that do not depend on time, the
/// term's closed form where it has one (TimeDerivativeTerm), a central
/// difference otherwise.
template <class Model>
Vec3 torque_time_derivative(const Model& model, const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) {
  if constexpr (!Model::time_dependent) {
    return Vec3::Zero();
  } else {
    auto one = [&](const auto& term) -> Vec3 {
      using T = std::decay_t<decltype(term)>;
      if constexpr (!T::traits.time_dependent) {
        return Vec3::Zero();
      } else if constexpr (system::TimeDerivativeTerm<T>) {
        return term.torque_time_derivative(R, Pi, Omega, t);
      } else {
        const double d = std::cbrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, std::abs(t));
        return (term.torque(R, Pi, Omega, t + d) - term.torque(R, Pi, Omega, t - d)) / (2.0 * d);
      }
    };
    return std::apply([&](const auto&... term) -> Vec3 { return (one(term) + ...); }, model.terms);
  }
}

struct OmegaRateJacobian {
  Mat3 attitude = Mat3::Zero();  // ∂Ω̇/∂η, body-side perturbation R → R exp(η̂)
  Mat3 omega = Mat3::Zero();     // ∂Ω̇/∂Ω
  Vec3 time = Vec3::Zero();      // ∂Ω̇/∂t
};

template <class Model>
OmegaRateJacobian omega_rate_jacobian(const Model& model, const Mat3& R, const Vec3& Omega, double t) {
  const Vec3 Pi = model.inertia.J * Omega;
  const auto K = model.momentum_rate_jacobian(R, Pi, Omega, t);
  OmegaRateJacobian out;
  out.attitude = model.inertia.J_inv * K.attitude;
  out.omega = model.inertia.J_inv * K.momentum * model.inertia.J;
  out.time = model.inertia.J_inv * torque_time_derivative(model, R, Pi, Omega, t);
  return out;
}

/// dτ for an arbitrary change dR of a matrix R that need not be orthogonal
/// (the matrix chart carries R in ℝ⁹). A torque linear in the attitude
/// (TermTraits::linear_in_attitude: gravity's Γ × m g χ with Γ = Rᵀe3, a
/// dipole's μ × RᵀB) is linear in R's entries, so its differential is the same
/// torque evaluated at dR: exact. For the other terms the differential is taken on
/// the rotation part, η = vee(Rᵀ dR): exact where R is orthogonal and dR is
/// tangent (dR = R η̂), and off by O(|RᵀR − I|) otherwise.
template <class Model>
Vec3 matrix_torque_differential(const Model& model, const Mat3& R, const Vec3& Omega, const Mat3& dR, double t) {
  if constexpr (!Model::has_torque) {
    return Vec3::Zero();
  } else {
    const Vec3 Pi = model.inertia.J * Omega;
    auto one = [&](const auto& term) -> Vec3 {
      using T = std::decay_t<decltype(term)>;
      if constexpr (T::traits.linear_in_attitude) {
        return term.torque(dR, Pi, Omega, t);  // linear in R
      } else {
        return term.torque_jacobian_attitude(R, Pi, Omega, t) * lie::vee(R.transpose() * dR);
      }
    };
    return std::apply([&](const auto&... term) -> Vec3 { return (one(term) + ...); }, model.terms);
  }
}

}  // namespace lgi::integrators::baselines
