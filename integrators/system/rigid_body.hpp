#pragma once
// The rigid body with a fixed point (or free), in body form on SO(3) × ℝ³:
//   Ṙ = R Ω̂,  Π̇ = Π × Ω + τ(R, Π, t),  Ω = J⁻¹ Π        (Euler–Poisson)
// (docs/conventions.md §4; Holm, Geometric Mechanics I, §6; seed 003 of docs/sources.md).
// The model is a variadic template over its torque terms (any types satisfying
// the TorqueTerm concept, terms/torque_term.hpp): the torque, the potential and
// the Jacobians are folds over the terms, resolved at compile time. Schemes ask
// the model, never a term by name, whether every term has a capability.
#include <tuple>
#include <type_traits>

#include "integrators/system/inertia.hpp"
#include "integrators/system/terms/discrete_gradient_term.hpp"
#include "integrators/system/terms/frozen_kick_term.hpp"
#include "integrators/system/terms/time_derivative_term.hpp"
#include "integrators/system/terms/torque_term.hpp"
#include "lie/product_state.hpp"

namespace lgi::system {

using State = lie::SO3xR3;  // (R, Π): attitude and body angular momentum

template <TorqueTerm... Terms>
struct RigidBody {
  Inertia inertia;
  std::tuple<Terms...> terms;

  static constexpr bool has_torque = sizeof...(Terms) > 0;
  static constexpr bool time_dependent = (Terms::traits.time_dependent || ... || false);
  /// Every term has an exact kick at frozen attitude (split-exact).
  static constexpr bool frozen_kick = (FrozenKickTerm<Terms> && ... && true);
  /// Every term has a discrete torque for the Cayley midpoint step (simo-wong).
  static constexpr bool discrete_gradient = (DiscreteGradientTerm<Terms> && ... && true);

  /// Whether the torque derives from a potential for the parameters at hand.
  bool is_conservative() const {
    return std::apply([](const auto&... term) { return (term.is_conservative() && ... && true); }, terms);
  }

  /// Calls f(term) for each term, in order.
  template <class F>
  void for_each_term(F&& f) const {
    std::apply([&](const auto&... term) { (f(term), ...); }, terms);
  }

  Vec3 omega(const Vec3& Pi) const { return inertia.J_inv * Pi; }

  /// The rows of R that torque() reads (bit i: row i; TermTraits::attitude_rows)
  /// over the terms in use; a Declared term that is off reads none.
  unsigned attitude_rows() const {
    unsigned rows = 0;
    for_each_term([&](const auto& term) { rows |= attitude_rows_of(term); });
    return rows;
  }

  /// Body torque, the sum of the declared terms (zero for a free body, at no cost).
  Vec3 torque(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    if constexpr (!has_torque) {
      return Vec3::Zero();
    } else {
      // The lambda returns Vec3, not an Eigen expression that would outlive its operands.
      return std::apply([&](const auto&... term) -> Vec3 { return (term.torque(R, Pi, Omega, t) + ...); }, terms);
    }
  }

  /// Π̇ = Π × Ω + τ.
  Vec3 momentum_rate(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    if constexpr (!has_torque) {
      return Pi.cross(Omega);
    } else {
      return Pi.cross(Omega) + torque(R, Pi, Omega, t);
    }
  }

  // ---- Jacobians (implicit schemes). Perturbations: R → R exp(η̂) (body
  // side, η ∈ ℝ³) and Π → Π + δΠ with Ω = J⁻¹Π following. Exact closed
  // forms; tests/test_model_jacobian.cpp checks them by central differences.

  /// ∂Ω/∂Π = J⁻¹ (Ω does not depend on R).
  const Mat3& omega_jacobian() const { return inertia.J_inv; }

  /// ∂τ/∂η at η = 0, the sum over the declared terms.
  Mat3 torque_jacobian_attitude(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    if constexpr (!has_torque) {
      return Mat3::Zero();
    } else {
      return std::apply(
          [&](const auto&... term) -> Mat3 { return (term.torque_jacobian_attitude(R, Pi, Omega, t) + ...); }, terms);
    }
  }
  /// dτ/dΠ (through Ω = J⁻¹Π where a term depends on Ω).
  Mat3 torque_jacobian_momentum(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    if constexpr (!has_torque) {
      return Mat3::Zero();
    } else {
      return std::apply(
          [&](const auto&... term) -> Mat3 {
            return (term.torque_jacobian_momentum(R, Pi, Omega, t, inertia.J_inv) + ...);
          },
          terms);
    }
  }

  /// Derivatives of the momentum field K(R, Π, t) = Π × Ω + τ.
  struct MomentumRateJacobian {
    Mat3 attitude;  // ∂K/∂η = ∂τ/∂η
    Mat3 momentum;  // ∂K/∂Π = Π̂ J⁻¹ − Ω̂ + dτ/dΠ
  };
  /// δ(Π × Ω) = δΠ × Ω + Π × J⁻¹δΠ = (Π̂ J⁻¹ − Ω̂) δΠ.
  MomentumRateJacobian momentum_rate_jacobian(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    MomentumRateJacobian jac;
    jac.momentum = lie::hat(Pi) * inertia.J_inv - lie::hat(Omega);
    if constexpr (!has_torque) {
      jac.attitude.setZero();
    } else {
      jac.attitude = torque_jacobian_attitude(R, Pi, Omega, t);
      jac.momentum += torque_jacobian_momentum(R, Pi, Omega, t);
    }
    return jac;
  }

  double kinetic_energy(const Vec3& Pi) const { return 0.5 * Pi.dot(omega(Pi)); }
  double potential_energy(const Mat3& R) const {
    if constexpr (!has_torque) {
      return 0.0;
    } else {
      return std::apply([&](const auto&... term) { return (term.potential(R) + ...); }, terms);
    }
  }
  /// H = ½ Π·J⁻¹Π + V(R).
  double energy(const State& s) const { return kinetic_energy(s.Pi) + potential_energy(s.R); }

  /// M(R): the part of the torque that derives from the potential.
  Vec3 potential_torque(const Mat3& R) const {
    if constexpr (!has_torque) {
      return Vec3::Zero();
    } else {
      Vec3 M = Vec3::Zero();
      for_each_term([&](const auto& term) { M += term.potential_torque(R); });
      return M;
    }
  }
};

using FreeBody = RigidBody<>;

}  // namespace lgi::system
