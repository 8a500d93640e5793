#pragma once
// The Poincaré section of the Cardan top on T³ (docs/cardan.md §9; seed 003,
// "Topology of surface of section", T³-dynamics) and the orbits `lgi
// poincare` runs for it.
//
// The section. With a vertical outer axis, the body's axis e3 has the height
// Γ·e3 = cos q2, and Richter's section S = d(Γ·e3)/dt = 0 becomes
//   S = −sin q2 · q̇2 = 0.
// It has two kinds of points:
// - q̇2 = 0: one point of the shape torus (q2, q3) (the "Poisson torus") per
//   crossing, on one of two copies told apart by the sign of q̇3
//   (piece +1, −1);
// - sin q2 = 0 (q2 = 0 or π, the body's axis on the outer axis): at such a
//   configuration every velocity lies in S = 0, so these crossings fill two
//   cylinders S¹ × (0, π) of (q3, ψ), ψ the direction of the shape velocity,
//   ψ = atan2(q̇3, q̇2) (piece 2 at q2 = 0, piece 3 at q2 = π).
// The cylinders' edges ψ = ±π/2 (q̇2 = 0) are glued to the two torus copies
// along the circles q2 ∈ {0, π}, where three sheets meet: the surface is not
// a manifold (seed 003), but it shows every orbit at (h, ℓ).
//
// Initial states on {q1 = 0, H = h, p1 = ℓ}: the shape r = (q2, q3) uniform
// on T² among {U_ℓ(r) ≤ h} (rejection, analysis/cardan_equilibria.hpp), then
// the shape velocity u = (q̇2, q̇3) uniform in angle on the ellipse
// ½ uᵀ S u = h − U_ℓ(r), S the Schur complement of M₁₁ in M, and
// q̇1 = (ℓ − M₁₂ q̇2 − M₁₃ q̇3)/M₁₁ (so p1 = ℓ). Seeded per orbit.
//
// The orbits run on the one time loop (integrators/core/stepper_loop.hpp), and
// the crossings of the two factors are its events (integrators/core/events.hpp),
// located on the scheme's own step map by the loop's root finder.
#include <atomic>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "integrators/ensemble/ensemble.hpp"
#include "integrators/system/cardan.hpp"

namespace lgi::experiments {

struct CardanCrossing {
  double t = 0.0;
  system::TorusState x{};
  int piece = 1;           // +1, −1: the torus copies (sign of q̇3); 2, 3: the cylinders at q2 = 0, π
  double x_coord = 0.0;    // q3 in [0, 2π)
  double y_coord = 0.0;    // pieces ±1: q2 in [0, 2π); pieces 2, 3: ψ in (−π, π]
  int direction = 1;       // the sign of dS/dt
};

struct CardanOrbitRequest {
  std::string scheme = "cardan-rk4";  // a fixed-step scheme of the T³ registry
  double t_end = 0.0, dt = 0.0;
  std::int64_t max_crossings = 100000;
  bool indicators = false;
  std::uint64_t seed = 0;
  const std::atomic<bool>* interrupt = nullptr;  // Ctrl-C: read every step of the orbit and of its indicators
};

struct CardanOrbit {
  int status = 0;  // 0 ok, 1 the run stopped, 2 no initial state, 3 too many crossings
  std::string reason;
  std::int64_t steps = 0;
  double cpu_seconds = 0.0;
  system::TorusState initial{}, final{};
  double max_energy_error = 0.0;    // max |H − H0| / max(|H0|, T0), T0 the initial kinetic energy
  double max_momentum_error = 0.0;  // max |p1 − p1(0)| / |p1(0)|
  std::vector<CardanCrossing> crossings;
  double lyapunov = 0.0, megno = 0.0;
};

/// The two factors of S = −sin q2 · q̇2 (top of this file): 0 is q̇2, 1 is sin q2.
double cardan_section_factor(const system::CardanTop& top, const system::TorusState& x, int which);

/// The crossing at x of the factor `which` (its piece and coordinates as lgi poincare writes them).
CardanCrossing cardan_crossing_at(const system::CardanTop& top, const system::TorusState& x, double t, int which,
                                  int direction);

/// The state over a point (x, y, piece) of the section at (ℓ, h), q1 = 0, p1 = ℓ (the inverse of
/// cardan_crossing_at): pieces ±1, q = (0, y, x) with q̇2 = 0 and the sign of q̇3 the piece; pieces 2, 3,
/// q = (0, 0 or π, x) with the shape velocity along ψ = y; its length from ½ uᵀ S u = h − U_ℓ (S the
/// Schur complement of M₁₁). False where U_ℓ > h (no state) or M is singular there.
bool cardan_section_state(const system::CardanTop& top, double l, double h, double x, double y, int piece,
                          system::TorusState& state);

/// Throws UsageError naming --scheme unless `name` is a fixed-step T³ scheme.
void check_cardan_section_scheme(const std::string& name);

/// The initial state of orbit `index` (top of this file); false if the level
/// set at q1 = 0 was not hit in 10⁵ draws.
bool draw_cardan_level_point(const system::CardanTop& top, double l, double h, std::uint64_t seed,
                             std::int64_t index, system::TorusState& x);

/// λ and ⟨Y⟩(t_end) of the orbit from x0 (RK4 on the state and its tangent with
/// steps dt: scalar_cardan_tangent_step, integrators/ensemble/cardan_tangent_ensemble.hpp),
/// the tangent vector drawn from (seed, index); NaN where the run blew up or a
/// set `stop` flag ended it.
void cardan_orbit_indicators(const system::CardanTop& top, const system::TorusState& x0, double t_end, double dt,
                             std::uint64_t seed, std::int64_t index, double& lyapunov, double& megno,
                             const std::atomic<bool>* stop = nullptr);
/// The same for the orbits x0[k] (index[k]), bit for bit, run together in the
/// SIMD lanes of a CardanTangentEnsemble on `isa` (one orbit at a time without).
void cardan_orbit_indicators(const system::CardanTop& top, std::span<const system::TorusState> x0, double t_end,
                             double dt, std::uint64_t seed, std::span<const std::int64_t> index,
                             std::optional<integrators::ensemble::Isa> isa, std::span<double> lyapunov,
                             std::span<double> megno, const std::atomic<bool>* stop = nullptr);

/// One orbit: its crossings and, on request, its indicators
/// (integrators/core/torus_tangent_flow.hpp, a separate pass).
CardanOrbit cardan_orbit(const system::CardanTop& top, const system::TorusState& x0, const CardanOrbitRequest& r,
                         std::int64_t index);

}  // namespace lgi::experiments
