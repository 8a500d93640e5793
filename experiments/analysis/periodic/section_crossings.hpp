#pragma once
// A Poincaré section as a phase condition and the crossings of an orbit with
// it, for `lgi periodic --seeds-from-poincare` and the manifolds of
// hyperbolic orbits (experiments/PERIODIC.md "Seeds from a section",
// "Manifolds").
//
// The section function is that of `lgi poincare`:
// - a heavy top (docs/atlas.md §6): Richter's S = (Γ × Ω)·e = Ω·(e × Γ),
//   gradient (J⁻¹(e × Γ), Ω × e); or S = Γ·e, gradient (0, e);
// - a Cardan top with a cyclic q1 (docs/cardan.md §9.2): S = −sin q2 · q̇2 =
//   d(cos q2)/dt, a product. Its zero set is two smooth hypersurfaces, q̇2 = 0
//   (the torus pieces ±1) and sin q2 = 0 (the cylinders 2, 3), which meet where
//   both vanish and ∇S = 0. So the phase condition is the factor that vanishes
//   at the orbit's point (PhaseSection::cardan_factor), smooth with a nonzero
//   gradient everywhere, and the crossings are those of either factor (as lgi
//   poincare tracks them, analysis/cardan_section.hpp), with lgi poincare's
//   coordinates (x, y, piece) in the places of (φ, ϑ, sheet).
// Crossings are found on the shooting integrator's step map (periodic_flow.hpp,
// flow_step): a sign change of a factor over a step of size dt is refined by
// the Illinois regula falsi on the length τ of one step from the step's start
// (the same map with a shorter step), to |factor| ≤ 1e-13 or τ to 4 ulps.
#include <vector>

#include "experiments/analysis/periodic/periodic_flow.hpp"
#include "experiments/analysis/poincare_section.hpp"

namespace lgi::experiments {

struct PhaseSection {
  SectionKind kind = SectionKind::richter;  // a heavy top's section and its axis
  Vec3 axis = Vec3::UnitZ();
  // A Cardan top's S = −sin q2 · q̇2: the factor of the phase condition, 0 (q̇2) or 1 (sin q2); −1 a heavy top.
  int cardan_factor = -1;
};

/// The phase function (a heavy top's S; a Cardan top's factor cardan_factor) and its gradient.
double section_value(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x);
Vec6 section_gradient(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x);

/// dS/dt of the whole section function along the flow: its sign is a crossing's direction.
double section_rate(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x);

/// The section s with, on a Cardan top, the phase factor the one that vanishes at x (nearest zero, each
/// factor scaled to [−1, 1]: sin q2 and q̇2/|q̇|); s itself for a heavy top.
PhaseSection section_at(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x);

/// (φ, ϑ, sheet) of a point on the section, as `lgi poincare` writes them
/// (a Cardan top: its (x, y, piece) of the factor vanishing at x).
SectionPoint section_coordinates(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x);

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
std::vector<SectionCrossing> section_crossings(const PeriodicFlow& flow, const PhaseSection& s, const Vec6& x0,
                                               double t_span, double dt, std::size_t max_count, int direction,
                                               bool& ok);

/// Minimum-norm Newton steps onto the invariants' levels at (h, l) (H = h, Π·Γ = l, |Γ|² = 1; a Cardan top
/// H = h, p1 = l, q1 = 0) and, with a section, its phase function = 0.
/// False if it does not reach them to 1e-13.
bool project_to_level(const PeriodicFlow& flow, Vec6& x, double h, double l, const PhaseSection* section);

}  // namespace lgi::experiments
