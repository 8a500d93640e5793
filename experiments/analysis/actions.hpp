#pragma once
// Action variables of the integrable tops (formulas, charts and sources:
// docs/actions.md; the command: experiments/ACTIONS.md).
//
// Every torus of an integrable top is a 3-torus in T*SO(3) and carries three
// actions I = (1/2π)∮ p dq, one per cycle of a basis, and the frequencies
// ω = ∂H/∂I of its flow. The canonical coordinates are the ZXZ Euler angles
// of docs/conventions.md §2 (ψ precession about the vertical, θ nutation, φ
// spin) with p_ψ = ℓ = Π·Γ, p_θ = Π1 cosφ − Π2 sinφ, p_φ = Π3, and for the free
// body the Andoyer–Deprit chart (docs/actions.md §2).
//
// - Lagrange top (A1 = A2 = A, A3 = C, mgχ = (0, 0, w), w ≠ 0):
//   I = (ℓ, L3, I_θ), L3 = Π3, I_θ = (1/π)∫ p_θ dθ between the turning points
//   of the cubic, in complete elliptic integrals (docs/actions.md §1);
//   ω = (ω_ψ, ω_φ, ω_θ) from the ratios of period integrals.
// - Euler top (free body, J diagonal): I = (ℓ, G, I_l), G = |Π|, I_l the
//   Deprit action of the chart whose pole is the axis of the largest moment,
//   with complete elliptic integrals of the third kind (docs/actions.md §2);
//   ω = (0, ω_g, ω_l).
// - Any top, numerically (docs/actions.md §3): the reduced torus at fixed ℓ
//   cut by a section F = c transverse to the flow (actions_section.hpp); the
//   rotation number of the return map from the order of the points along the
//   curve, the mean return time by a weighted Birkhoff average, the section curve's
//   action from a Fourier fit in the conjugating angle, the other action from
//   the time average of p_θ θ̇ + p_φ φ̇ = 2T − ℓψ̇.
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "experiments/analysis/actions_section.hpp"
#include "experiments/analysis/relative_equilibria.hpp"
#include "integrators/system/rigid_body.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// The Lagrange top's parameters: J = diag(A, A, C), m g χ = (0, 0, w).
struct LagrangeBody {
  double A = 1.0, C = 1.0, w = 1.0;
};

/// One torus of a Lagrange top in closed form.
struct LagrangeActions {
  Vec3 actions = Vec3::Zero();      // (ℓ, L3, I_θ)
  Vec3 frequencies = Vec3::Zero();  // (ω_ψ, ω_φ, ω_θ) = ∂H/∂(ℓ, L3, I_θ)
  double period = 0.0;              // nutation period 2π/ω_θ
  double u1 = 0.0, u2 = 0.0, u3 = 0.0;  // roots of the cubic in u = cos θ (turning points u1 ≤ u2)
};

/// The torus (ℓ, L3, h), or nothing where it is empty or degenerate (a
/// relative equilibrium, u1 = u2, or w = 0).
std::optional<LagrangeActions> lagrange_actions(const LagrangeBody& body, double l, double L3, double h);

/// The same action I_θ by Gauss–Legendre quadrature of (A/π)∫√f/(1 − u²) du
/// in the Legendre angle (an independent check of the closed form).
double lagrange_nutation_action_quadrature(const LagrangeBody& body, double l, double L3, double h, int nodes);

/// The Lagrange body of a heavy top, or nothing if it is not one (J diagonal
/// with J1 = J2 to 1e-12, mgχ on e3 and nonzero).
std::optional<LagrangeBody> lagrange_body(const HeavyTopBody& body);

/// One torus of the Euler top in closed form.
struct EulerActions {
  Vec3 actions = Vec3::Zero();      // (ℓ, G, I_l)
  Vec3 frequencies = Vec3::Zero();  // (0, ω_g, ω_l)
  double period = 0.0;              // period of Π(t)
  int around = 0;                   // the body axis (0, 1, 2) that Π circulates about
  int pole = 0;                     // the chart's pole: the axis of the largest moment
};

/// The torus through (Π, ℓ) of the free body with J = diag(moments) (distinct
/// moments), or nothing on a separatrix or a steady rotation.
std::optional<EulerActions> euler_actions(const Vec3& moments, const Vec3& Pi, double l);

/// The torus (ℓ, G, h) of the same body: the Π orbit of energy h on |Π| = G
/// circulating about `around` (the smallest or the largest axis).
std::optional<EulerActions> euler_actions_at(const Vec3& moments, double l, double G, double h);

/// The energy surface H = h in action space: the closed-form tori on a grid of
/// n × n values of (ℓ, L3) (Lagrange: |ℓ|, |L3| ≤ √(2 max(A, C)(h + |w|)); an even n is raised
/// to n + 1 so that the grid holds ℓ = L3 = 0 and both lines ℓ = ±L3) or
/// of (G, ℓ) (Euler: G between √(2h J_min) and √(2h J_max), |ℓ| ≤ G); points
/// without a torus are left out. `keep_going`, if given, is called before each row of the
/// grid (--grid 2000: seconds in all); false stops: the rows so far.
std::vector<LagrangeActions> lagrange_surface(const LagrangeBody& body, double h, int n,
                                              const std::function<bool()>& keep_going = {});
std::vector<EulerActions> euler_surface(const Vec3& moments, double h, int n,
                                        const std::function<bool()>& keep_going = {});

/// n initial states on {H = h, Π·Γ = ℓ}: Γ on a Fibonacci lattice of the
/// accessible directions (U_ℓ(Γ) < h), Π = ℓJΓ/(Γ·JΓ) + u with u ⊥ Γ at a
/// golden-angle phase on the ellipse of the remaining kinetic energy
/// (docs/atlas.md §6); R with Rᵀe3 = Γ. Fewer than n if the region is small.
std::vector<system::State> level_set_states(const HeavyTopBody& body, double l, double h, int n);

/// The actions of a numerical torus (docs/actions.md §3).
struct NumericalTorusOptions {
  /// An explicit symplectic composition of order 8 (Kahan & Li's 8th order over the symmetric
  /// splitting): the fit of the section curve needs the orbit on its torus to ~1e-8, which a
  /// 4th-order scheme at the scenes' dt = 0.01 misses by 1e-5–1e-3 (experiments/ACTIONS.md).
  static constexpr const char* default_scheme = "split-symmetric@kahan-li8";
  std::string scheme = default_scheme;
  double dt = 1e-2;
  int crossings = 400;  // section crossings used (the run stops after this many)
  int max_extend = 8;   // up to max_extend × crossings where the points do not resolve the curve (§3 step 3)
  int harmonics = 128;   // most Fourier modes of the section curve (fewer where the points cannot resolve them)
  int refine_harmonics = 48;  // Fourier modes of the fits that refine ρ
  double max_time = 1e5;
  double max_fit_residual = 1e-6;   // above it the torus is not ok (docs/actions.md §3)
  double min_section_window = 0.05;  // narrowest window free of turning values for a section
  int pilot_turns = 100;             // turning points of Γ3 in the pilot run that chooses the section
  double min_pole_distance = 1e-3;   // rad: a section curve closer to Γ = ±e3 is refused (reason 7)
};

/// Why a numerical torus failed (the `reason` column of /tori, experiments/ACTIONS.md).
enum class TorusFailure : int {
  none = 0,        // ok
  scheme = 1,      // unknown scheme
  no_section = 2,  // no coordinate of (Π, Γ) has a level free of turning values
  crossings = 3,   // fewer section crossings than asked before max_time (or the run failed)
  periodic = 4,    // the section is one point: a periodic orbit, not a 2-torus
  resonance = 5,   // the points leave gaps in kρ (near a resonance)
  fit = 6,         // the section is not k ≤ 6 smooth circles (fit residual too large)
  chart_pole = 7,  // the section curve passes through the Euler-angle chart's pole Γ = ±e3
};

struct NumericalTorus {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double l = 0.0, h = 0.0;
  double action_a = nan;  // (1/2π)∮ p dq along the section curve (oriented so that it is ≥ 0); NaN if not ok
  double action_b = nan;  // along k returns of the flow closed by an arc of the section curve; NaN if not ok
  double rotation_number = nan;  // of the k-th return map, in the orientation of cycle a (lifted, §3 step 4)
  double return_time = nan;      // mean return time
  double omega_a = nan, omega_b = nan;  // ∂H/∂I_a = 2πρ/(kT̄), ∂H/∂I_b = 2π/(kT̄)
  double mean_pq = nan;          // time average of p_θ θ̇ + p_φ φ̇
  double fit_residual = nan;     // largest residual of the Fourier fit (Π relative to its largest |Π|)
  SectionChoice section;         // the section F = c (docs/actions.md §3, step 1)
  int winding = 0;               // turns of φ along the section curve
  int circles = 0;               // k: the section cuts k circles, cycle b is k returns
  std::vector<Point6> circle;    // (Π, Γ) of cycle a's section points in the order met (α_j = jρ), if ok
  int crossings = 0;
  double t_end = 0.0;
  bool ok = false;
  int reason = 0;                // a TorusFailure
  std::string status;
};

NumericalTorus numerical_torus(const system::Scene& scene, const system::State& x0,
                               const NumericalTorusOptions& options);

/// Measured Lagrange data from one integrated orbit (the check of the closed
/// form): the nutation period from located turning points, then one period
/// integrated with `steps` fixed steps and the periodic trapezoid rule.
struct MeasuredLagrange {
  double period = 0.0;
  double action_theta = 0.0;  // (1/2π)∫ p_θ θ̇ dt over one period
  Vec3 frequencies = Vec3::Zero();  // (Δψ, Δφ, 2π)/period
  bool ok = false;
};
MeasuredLagrange measure_lagrange(const system::Scene& scene, const system::State& x0, const std::string& scheme,
                                  double dt, int steps, int periods);

/// Measured Euler data: one period of Π (given) integrated with `steps` fixed
/// steps: (1/2π)|∮ L dl| in the pole's chart and the mean precession of the
/// pole axis about m.
struct MeasuredEuler {
  double action_l = 0.0;       // (1/2π)|∮ Π_pole dl|
  double omega_g = 0.0;        // Δψ_pole / period
  bool ok = false;
};
MeasuredEuler measure_euler(const system::Scene& scene, const system::State& x0, const std::string& scheme,
                            double period, int steps, int pole);

}  // namespace lgi::experiments
