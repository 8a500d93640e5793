#pragma once
// A term with a discrete torque for the Cayley midpoint step of simo-wong
// (integrators/schemes/simo_wong.hpp, where the discrete equations are derived):
// R_{n+1} = R_n cay(ξ), ξ = hW, and the term's τ_d is chosen so that
// τ_d·ξ = −[V(R_{n+1}) − V(R_n)] (the energy balance; Gonzalez, J. Nonlinear
// Sci. 6 (1996) 449–467) for a potential, or τ at the midpoint otherwise.
#include <concepts>
#include <utility>

#include "integrators/system/terms/torque_term.hpp"

namespace lgi::system {

/// One Cayley midpoint step, as the terms see it.
struct CayleyStep {
  const Mat3* R = nullptr;  // R_n
  Mat3 R1;                  // R_{n+1} = R_n cay(ξ)
  Mat3 Ainv;                // (I + ξ̂/2)⁻¹: x_mid = Ainv x_n for x_{n+1} = cay(ξ)ᵀ x_n
  Vec3 xi;                  // ξ = hW
  Vec3 W;                   // the midpoint angular velocity (the unknown)
  double theta2 = 0.0;      // |ξ|²
  double h = 0.0;
  double t_mid = 0.0;
};

/// What the terms add to: τ_d, the Jacobian of the residual
/// F(W) = 2JW − 2Π_n − h (JW) × W − h τ_d (the scheme puts the Jacobian of
/// its own part there first; each term adds −h ∂τ_d/∂W), the
/// sum of the magnitudes of the contributions (for the convergence test), and
/// the rounding a term's τ_d carries beyond a few ulps of those magnitudes.
struct DiscreteTorque {
  Vec3 tau = Vec3::Zero();
  Mat3 jacobian = Mat3::Zero();
  double magnitude = 0.0;
  double noise = 0.0;
};

template <class T>
concept DiscreteGradientTerm = TorqueTerm<T> && requires(const T& term, const Mat3& R, const CayleyStep& step,
                                                         DiscreteTorque& out) {
  typename T::DiscreteStart;  // what the term keeps from R_n for the Newton iterations
  { term.discrete_start(R) } -> std::same_as<typename T::DiscreteStart>;
  term.add_discrete_torque(std::declval<const typename T::DiscreteStart&>(), step, out);
};

}  // namespace lgi::system
