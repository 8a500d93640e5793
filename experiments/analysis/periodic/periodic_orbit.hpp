#pragma once
// One periodic orbit of the Euler–Poisson flow in (Π, Γ) ∈ ℝ⁶ at fixed
// (h, ℓ), by single shooting with Newton's method, and its Floquet
// multipliers (experiments/PERIODIC.md; R. Seydel, Practical Bifurcation and
// Stability Analysis, 3rd ed. (2010), ch. 7).
//
// Unknowns z = (x0, T) ∈ ℝ⁷; equations (ten)
//   φ_T(x0) − x0 = 0,                    (6)
//   ⟨f(x_ref), x0 − x_ref⟩ = 0,          (phase: x0 on the hyperplane through x_ref ⊥ the flow)
//   H(x0) = h, Π·Γ = ℓ, |Γ|² = 1.
// The monodromy M = ∂φ_T/∂x0 has four multipliers at 1 (flow, H and the two
// Casimirs), so φ_T − x0 alone is singular; the full system has rank 7 at an
// isolated orbit. Each Newton step is the minimum-norm least-squares solution
// (complete orthogonal decomposition, rank threshold 1e-9 relative).
// Degenerate: the system's rank is below 7 (its smallest singular value below
// 1e-7 of the largest) and all six multipliers are within 1e-5 of 1: the
// orbit lies in a continuum of periodic orbits at the same (h, ℓ), a resonant
// torus of an integrable top, and is not isolated.
#include <array>
#include <complex>
#include <string>

#include "experiments/analysis/periodic/euler_poisson_flow.hpp"

namespace lgi::experiments {

struct ShootingSettings {
  double dt = 2e-3;          // the step bound; a shot takes ⌈T/dt⌉ equal steps
  double tolerance = 1e-10;  // on the residual (below)
  int max_iterations = 30;
};

struct PeriodicOrbit {
  Vec6 x0 = Vec6::Zero();  // (Π, Γ): a point of the orbit
  double period = 0.0, h = 0.0, l = 0.0;
  double residual = 0.0;   // max(|φ_T(x0) − x0|, |H − h|, |Π·Γ − ℓ|, ||Γ|² − 1|)
  Mat6 monodromy = Mat6::Identity();
  std::array<std::complex<double>, 6> multipliers{};  // the four nearest 1 first, then the nontrivial pair
  std::string stability;   // elliptic, hyperbolic, inverse_hyperbolic or complex (of the nontrivial pair)
  double trivial_deviation = 0.0;  // max |μ − 1| over the four nearest 1
  double product_deviation = 0.0;  // |∏ μ − 1|
  double rank_ratio = 0.0;         // smallest / largest singular value of the Newton system
  bool degenerate = false;
  bool converged = false;
  int iterations = 0;
};

/// Newton from (x_guess, T_guess) towards the orbit at (h, l); the phase
/// hyperplane passes through x_guess.
PeriodicOrbit correct_orbit(const HeavyTopBody& body, const Vec6& x_guess, double T_guess, double h, double l,
                            const ShootingSettings& s);

/// Multipliers, their checks, the stability class and the degeneracy of a corrected orbit.
void classify_orbit(PeriodicOrbit& o);

}  // namespace lgi::experiments
