#pragma once
// Continuation of a family of periodic orbits in h at fixed ℓ (or in ℓ at
// fixed h: shooting.in_l; read p for h below), the location of its
// bifurcations, and branch switching at period doublings
// (experiments/PERIODIC.md "Families").
//
// Predictor–corrector (H. B. Keller, in Applications of Bifurcation Theory,
// Academic Press 1977, 359–384; R. Seydel, Practical Bifurcation and
// Stability Analysis, 3rd ed. (2010), §4.4): at the last regular orbit z_b ∈
// ℝ⁸ = (x0, T, h), the unit tangent t (the null vector of the corrector's ten
// equations, in the sense of the secant from the orbit before), the
// predictor z_b + Δs t, and the corrector of periodic_orbit.hpp with
// ⟨t, z − z_p⟩ = 0 (pseudo-arclength), so folds in h are passed. Δs is the
// length of the family's first step (a doubled family: the larger of its
// first chord and h_step). A step fails when the corrector does not converge
// or when its correction (orthogonal to t) exceeds 0.3 Δs, so that the new
// secant turns by less than about 17°: a guard against jumping to a
// neighbouring branch. A failed step is halved up to five times, then the
// family ends; after a success a halved Δs is doubled back. Why a family
// ended is written on its last row (`family_end`), with any event whose sign
// change was seen but not located.
//
// Events, from the trace of the section's monodromy P (periodic_orbit.hpp),
// between consecutive orbits a, b:
// - tr P + 2 changes sign: a multiplier passes −1, a period doubling;
// - tr P − 2 changes sign: the pair passes +1. With h turning there (the
//   orbit is a fixed point of the section map at fixed h, so the implicit
//   function theorem in h fails exactly where P has the eigenvalue 1), a fold;
//   else a class change (elliptic ↔ hyperbolic without a fold: a branch point).
// Each event is located by the Illinois variant of regula falsi on the
// position s ∈ (0, 1) along the chord from z_a to z_b (the corrector with
// ⟨z_b − z_a, z − z_p(s)⟩ = 0), to |tr P ∓ 2| ≤ 1e-9, and inserted as its own
// row with its `event`, in the order of s. A trace within 1e-8 of ±2 at either
// end is not counted as a sign (no events on round-off).
// Branch switching: at a period doubling the eigenvector v of P for −1 (in
// ℝ⁶: section_basis · v, made orthogonal to the parent's doubled tangent)
// starts the doubled family: two orbits with ⟨v, z − z_pd⟩ = ε, 2ε
// (ε = switch_amplitude |x_pd|), each checked to be of period within 10 % of
// 2T and not periodic with half its period; then the family is continued as
// any other; its `parent` is the family it branched from.
#include <string>
#include <vector>

#include "experiments/analysis/periodic/periodic_orbit.hpp"

namespace lgi::experiments {

struct FamilySettings {
  ShootingSettings shooting{};
  double amplitude = 1e-4;         // ε of the first orbit at an equilibrium, relative to |x_e|
  double switch_amplitude = 1e-3;  // ε of branch switching, relative to |x_pd|
  int steps = 10;                  // continuation steps after the first orbit
  double h_step = 0.0;             // the first step in h (> 0); later steps keep its arclength
  double start_h_step = 0.0;       // with shooting.in_l, a Lyapunov family's step in h from its first orbit
                                   // to the level h it is continued at in ℓ (0: h_step)
  double h_min = -INFINITY, h_max = INFINITY;  // the family stops where p (h, or ℓ with shooting.in_l) leaves them
  bool locate_events = true;
  bool switch_branches = true;     // start the doubled family at each period doubling
};

struct FamilyOrbit {
  int family = 0, index = 0;
  int equilibrium = -1;  // the row in equilibria_at(body, l) the family starts at (−1: a seed or a branch)
  int parent = -1;       // the family a doubled family branched from
  double omega = 0.0;    // ω of the mode it was started along (2π/T of the first orbit otherwise)
  std::string event = "none";  // none, fold, period_doubling or class_change
  std::string family_end;      // on a family's last row: why it ended, and events seen but not located
  PeriodicOrbit orbit;
};

/// Continues `rows` (one or more orbits of one family, the last the newest)
/// by up to s.steps further orbits, locating events on the way. `first_dh`
/// is the first step in h when rows holds one orbit; `equilibrium`, if
/// given, is the family's equilibrium (the first predictor scales about it).
/// ds0 > 0 sets the arclength step (else the length of the last chord).
void continue_rows(const PeriodicFlow& body, std::vector<FamilyOrbit>& rows, double first_dh, const Vec6* equilibrium,
                   double h_equilibrium, const FamilySettings& s, double ds0 = 0.0);

/// The doubled family started at a period-doubling row `pd`, numbered
/// `family` and continued by s.steps orbits in the sense that ε > 0 gives
/// (empty, with the reason in why_not, if no orbit of period ≈ 2T off the doubled one is found).
std::vector<FamilyOrbit> doubled_family(const PeriodicFlow& body, const FamilyOrbit& pd, int family,
                                        const FamilySettings& s, std::string& why_not);

}  // namespace lgi::experiments
