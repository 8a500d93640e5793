#pragma once
// What a torque term is: the C++20 concept every term of a model satisfies,
// and the optional capabilities some schemes need (docs/conventions.md §4 for
// the frames and signs).
//
// A term gives its body torque τ(R, Π, Ω, t), its potential V(R) (0 where it
// has none), the torque's derivatives for implicit schemes, and its traits.
// Jacobians use the schemes' body-side trivialisation R → R exp(η̂):
//   torque_jacobian_attitude(R, Π, Ω, t)      = ∂τ/∂η at η = 0;
//   torque_jacobian_momentum(R, Π, Ω, t, J⁻¹) = dτ/dΠ with Ω = J⁻¹Π following.
// tests/test_model_jacobian.cpp checks every term against central differences.
//
// Optional capabilities, each a concept of its own file:
//   frozen_kick_term.hpp      the torque is affine in Ω at frozen R and t
//                             (exact kicks of split-exact);
//   discrete_gradient_term.hpp a discrete torque for the Cayley midpoint
//                             step (simo-wong's energy–momentum property);
//   time_derivative_term.hpp  a closed-form ∂τ/∂t (Rosenbrock baselines).
#include <concepts>

#include "integrators/system/inertia.hpp"

namespace lgi::system {

/// Static facts about a term, read by schemes and by the registry.
struct TermTraits {
  bool time_dependent = false;      // τ depends on t
  bool momentum_dependent = false;  // τ depends on Π (through Ω), e.g. a damper
  /// τ = −(dV/dR) for some parameter values (a spring without damper); the
  /// run-time answer for the parameters at hand is is_conservative().
  bool may_be_conservative = false;
  /// V and τ are linear in the entries of R: V = c·(Rᵀ e) for a body vector c
  /// and a space-fixed vector e (gravity's Γ = Rᵀe3, a uniform field's Rᵀ B).
  /// Then τ at a non-orthogonal matrix is the same formula, and the
  /// Lie–Poisson reduction to (Π, Rᵀe) applies.
  bool linear_in_attitude = false;
  /// The rows of R that torque() reads, bit i for row i (gravity reads only
  /// Γ = Rᵀe3, row 2: 0b100). The RKMK schemes form only these rows of a
  /// stage's attitude and fill the others with NaN, so a term that reads a row
  /// it did not declare makes the run fail, never silently wrong
  /// (tests/test_attitude_rows.cpp checks every term). A term whose
  /// parameters narrow the rows (a magnetic field along one axis) also has a
  /// member `unsigned attitude_rows() const`, within this bound.
  unsigned attitude_rows = 0b111;
};

/// The rows of R a term's torque reads: its own attitude_rows() where its
/// parameters narrow them (or where it is a Declared slot), else its traits'.
template <class T>
unsigned attitude_rows_of(const T& term) {
  if constexpr (requires { term.attitude_rows(); }) return term.attitude_rows();
  else return T::traits.attitude_rows;
}

/// The scene's body, as the terms that depend on it need it.
struct BodyProperties {
  Mat3 inertia = Mat3::Identity();
  double mass = 0.0;
  Vec3 center_of_mass = Vec3::Zero();  // χ, body coordinates from the fixed point
};

template <class T>
concept TorqueTerm = requires(const T& term, const Mat3& R, const Vec3& v, double t) {
  { T::traits } -> std::convertible_to<TermTraits>;
  { term.torque(R, v, v, t) } -> std::same_as<Vec3>;
  { term.potential(R) } -> std::convertible_to<double>;
  /// The part of τ that derives from V (zero for a drive, and without a damper).
  { term.potential_torque(R) } -> std::same_as<Vec3>;
  { term.torque_jacobian_attitude(R, v, v, t) } -> std::same_as<Mat3>;
  { term.torque_jacobian_momentum(R, v, v, t, R) } -> std::same_as<Mat3>;
  { term.is_conservative() } -> std::same_as<bool>;
};

}  // namespace lgi::system
