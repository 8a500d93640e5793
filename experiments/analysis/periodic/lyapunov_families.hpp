#pragma once
// The Lyapunov centre families of the linearly stable relative equilibria at
// ℓ, continued in h (experiments/PERIODIC.md). Lyapunov's centre theorem
// (K. R. Meyer, G. R. Hall, D. Offin, Introduction to Hamiltonian Dynamical
// Systems and the N-Body Problem, 2nd ed. (2009), §9.2): for each
// non-resonant frequency ω of an elliptic equilibrium a family of periodic
// orbits leaves it, its period tending to 2π/ω.
//
// Start: x0 = x_e + ε u, u the real part of the eigenvector of iω of the
// linearisation (tangent to the levels of H, C and |Γ|², since their
// gradients are left null vectors of it), ε = `amplitude` |x_e|, projected
// back onto Π·Γ = ℓ, |Γ| = 1; h = H(x0); period guess 2π/ω. The first row's
// period differs from 2π/ω by O(ε²).
// Continuation: natural parameter in h, steps of `h_step` away from h_e
// (in the direction the family leaves in), the predictor the first orbit
// scaled from the equilibrium by √((h − h_e)/(h₀ − h_e)), then the secant
// through the last two orbits; a step that fails is halved up to four times,
// then the family stops (so a fold ends it: folds, period doublings and class
// changes are not located; every row's event is "none").
#include <vector>

#include "experiments/analysis/periodic/periodic_orbit.hpp"

namespace lgi::experiments {

struct FamilySettings {
  ShootingSettings shooting{};
  double amplitude = 1e-4;  // ε relative to |x_e|
  int steps = 10;           // continuation steps after the first orbit
  double h_step = 0.0;      // > 0
  double h_min = -INFINITY, h_max = INFINITY;  // the family stops outside
};

struct FamilyOrbit {
  int family = 0, index = 0;
  int equilibrium = 0;  // its row in equilibria_at(body, l)
  double omega = 0.0;   // ω of the mode it was started along
  PeriodicOrbit orbit;
};

/// The frequencies ω (ascending) of a linearly stable equilibrium, √(−μ) for
/// the roots μ of μ² + g1 μ + g2.
std::vector<double> equilibrium_frequencies(const RelativeEquilibrium& e);

/// Every family of every linearly stable equilibrium at l, in the order of
/// equilibria_at(body, l) then ascending ω; the families numbered from 0.
std::vector<FamilyOrbit> lyapunov_families(const HeavyTopBody& body, double l, const FamilySettings& s);

/// One family from a start (x0, T) at h (a seed): the orbit and the continuation as above, with
/// the secant predictor from the second step on.
std::vector<FamilyOrbit> continue_family(const HeavyTopBody& body, const Vec6& x0, double T, double h, double l,
                                         double direction, const FamilySettings& s);

}  // namespace lgi::experiments
