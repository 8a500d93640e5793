#pragma once
// A Poincaré section of the Euler–Poisson flow in (Π, Γ) ∈ ℝ⁶ as a phase
// condition and the crossings of an orbit with it, for `lgi periodic
// --seeds-from-poincare` and the manifolds of hyperbolic orbits
// (experiments/PERIODIC.md "Seeds from a section", "Manifolds").
//
// The section function is that of `lgi poincare` (docs/atlas.md §6):
// Richter's S = (Γ × Ω)·e = Ω·(e × Γ), gradient (J⁻¹(e × Γ), Ω × e); or
// S = Γ·e, gradient (0, e). Crossings are found on the sixth-order midpoint
// composition of euler_poisson_flow.hpp: a sign change of S over a step of
// size dt is refined by the Illinois regula falsi on the length τ of one
// step from the step's start (the same map with a shorter step), to
// |S| ≤ 1e-13 or τ to 4 ulps.
#include <vector>

#include "experiments/analysis/periodic/euler_poisson_flow.hpp"
#include "experiments/analysis/poincare_section.hpp"

namespace lgi::experiments {

struct PhaseSection {
  SectionKind kind = SectionKind::richter;
  Vec3 axis = Vec3::UnitZ();
};

/// S(x) and its gradient.
double section_value(const HeavyTopBody& body, const PhaseSection& s, const Vec6& x);
Vec6 section_gradient(const HeavyTopBody& body, const PhaseSection& s, const Vec6& x);

/// (φ, ϑ, sheet) of a point on the section, as `lgi poincare` writes them.
SectionPoint section_coordinates(const HeavyTopBody& body, const PhaseSection& s, const Vec6& x);

struct SectionCrossing {
  double t = 0.0;   // from the start (negative when integrated backwards)
  Vec6 x = Vec6::Zero();
  int direction = 1;  // the sign of dS/dt
};

/// The crossings of the orbit from x0 over t ∈ (0, t_span] (t_span < 0: backwards;
/// a start on the section is not one of them),
/// at most max_count of them (only those of `direction` if it is ±1; 0: both).
/// ok is false if a step failed or a signal came (interrupt_requested, read every step; the
/// crossings before it are returned).
std::vector<SectionCrossing> section_crossings(const HeavyTopBody& body, const PhaseSection& s, const Vec6& x0,
                                               double t_span, double dt, std::size_t max_count, int direction,
                                               bool& ok);

/// Minimum-norm Newton steps onto H = h, Π·Γ = l, |Γ|² = 1 and, with a section, S = 0.
/// False if it does not reach them to 1e-13.
bool project_to_level(const HeavyTopBody& body, Vec6& x, double h, double l, const PhaseSection* section);

}  // namespace lgi::experiments
