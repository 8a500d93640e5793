#pragma once
// The critical periodic orbits of the Kovalevskaya top and their place in the
// (h̃, k) diagram (experiments/PERIODIC.md "Kovalevskaya's top: critical
// orbits"; docs/atlas.md §9).
//
// At fixed ℓ the reduced flow has two degrees of freedom and the integrals H
// and K. Where dH and dK are dependent on the leaf {Π·Γ = ℓ, |Γ| = 1} (and
// dH ≠ 0 there) the Hamiltonian fields of H and K are parallel, so the orbit
// of the joint flow is a circle: a periodic orbit of H's flow, a critical
// circle of the Liouville foliation. Its (h̃, k) is a critical value of
// (H, K), so it lies on an Appelrot family (M. P. Kharlamov, Regul. Chaotic
// Dyn. 10 (2005) 381; A. V. Bolsinov, P. H. Richter and A. T. Fomenko,
// Sb. Math. 191 (2000) 151; the formulas of kovalevskaya_diagram.hpp). A
// nondegenerate critical circle is an isolated periodic orbit on its energy
// level, unlike the orbits of resonant tori (periodic_orbit.hpp, "degenerate").
//
// Seeds: the critical points of (H, K) found at an energy by the Lagrange
// solver of kovalevskaya_critical.hpp (one per distinct k), each with the
// period guessed as its first return to the hyperplane through it normal to
// the flow.
#include <cmath>
#include <string>
#include <vector>

#include "experiments/analysis/periodic/euler_poisson_flow.hpp"

namespace lgi::experiments {

/// The place of a state x = (Π, Γ) of a Kovalevskaya top in the (h̃, k) diagram.
struct AppelrotCheck {
  double k = NAN;          // K/c²
  int family = -1;         // the nearest Appelrot family within 1e-6 (1 + k); −1: none, or not a Kovalevskaya top
  double distance = NAN;   // |k − k_f(h̃)| / (1 + k) for the nearest family f at the same h̃
  double rank_gap = NAN;   // σ_min/σ_max of the rows dH, dK, dC, d|Γ|² (scaled top): 0 on the critical set
};

/// NaN and −1 for a body that is not a Kovalevskaya top (kovalevskaya_scale). The
/// families are taken at (l, h), an orbit's own level (its point is on it to the
/// orbit's residual); without them at Π·Γ and H of x. The level's ℓ matters at
/// ℓ = 0, where family 3 is the limit of family 2: a computed Π·Γ of 1e-17 would
/// label family 3's points family 2 (kovalevskaya_diagram.hpp).
AppelrotCheck appelrot_check(const HeavyTopBody& body, const Vec6& x, double l, double h);
AppelrotCheck appelrot_check(const HeavyTopBody& body, const Vec6& x);

/// A start on a critical circle: a point, the period guess and the critical value.
struct CriticalSeed {
  Vec6 x = Vec6::Zero();
  double period = 0.0;  // 0: no return found (failure says why)
  double h = 0.0, k = 0.0;
  int family = -1;      // the Appelrot family of (h̃, k)
  std::string failure;
};

/// The critical circles at (ℓ, h), unscaled, one per distinct k, from `lattice`
/// lattice states (kovalevskaya_critical_values). The return is integrated by
/// the shooting integrator with step dt for at most 500/√c. Empty for a body
/// that is not a Kovalevskaya top or an h below the least energy.
std::vector<CriticalSeed> kovalevskaya_critical_seeds(const HeavyTopBody& body, double l, double h, double dt,
                                                      int lattice = 24);

/// The time of the first return of the orbit from x0 to the hyperplane through x0
/// normal to the flow, in the flow's direction and within 1e-2 of the largest
/// distance reached (linear interpolation in the step); 0 if none before t_max or
/// once a signal came (interrupt_requested, read every step).
double hyperplane_return_time(const HeavyTopBody& body, const Vec6& x0, double dt, double t_max);

}  // namespace lgi::experiments
