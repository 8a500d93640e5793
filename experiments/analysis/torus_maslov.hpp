#pragma once
// The Maslov indices of the cycles a and b of a numerical torus (docs/actions.md §5),
// for EBK quantisation (docs/quantum.md §10).
//
// The tangent plane of a Liouville torus of an integrable top at fixed ℓ is spanned by
// the Hamiltonian fields X_H and X_K of the energy and the second integral. Written in
// the reduced canonical chart (θ, φ, p_θ, p_φ) of docs/actions.md as the columns of
// (Q; P), det(Q + iP) never vanishes on the torus, and the Maslov index of a loop is
// −(the change of arg det(Q + iP) along it)/π (V. I. Arnold, Funct. Anal. Appl. 1
// (1967) 1; the count of caustics with signs, J. B. Keller, Ann. Phys. 4 (1958) 180;
// the sign makes a libration run with the flow +2, as p = −sin t, q = cos t of an oscillator).
// - cycle a: along the section points of the torus in the order of α = jρ;
// - cycle b: from the mean rate r of arg det(Q + iP) along the flow,
//   −r = (μ_a ω_a + μ_b ω_b)/2, measured as a weighted Birkhoff average.
#include <functional>
#include <limits>
#include <string>

#include "experiments/analysis/actions.hpp"

namespace lgi::experiments {

/// A second integral K(Γ, Π) of the top (its gradient is taken by central differences).
using SecondIntegralFunction = std::function<double(const Vec3& gamma, const Vec3& Pi)>;

struct TorusMaslov {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  int mu_a = 0, mu_b = 0;
  double mu_a_measured = nan;  // −(the winding along the section points)/π (an integer up to round-off)
  double mu_b_measured = nan;  // (−2r − μ_a ω_a)/ω_b (an integer up to the Birkhoff average's error)
  double largest_step = nan;   // the largest change of arg det(Q + iP) between neighbouring section points
  bool ok = false;
  std::string status;
};

/// arg det(Q + iP) of the torus's tangent plane span(X_H, X_K) at (Γ, Π) (Γ off the chart's poles).
double lagrangian_phase(const HeavyTopBody& body, const SecondIntegralFunction& K, const Vec3& gamma,
                        const Vec3& Pi);

/// The Maslov indices of an ok numerical torus through x0, with its flow integrated again for
/// `returns` section crossings with the torus's scheme and step (options).
TorusMaslov torus_maslov(const system::Scene& scene, const HeavyTopBody& body, const system::State& x0,
                         const NumericalTorus& torus, const SecondIntegralFunction& K,
                         const NumericalTorusOptions& options, int returns = 200);

}  // namespace lgi::experiments
