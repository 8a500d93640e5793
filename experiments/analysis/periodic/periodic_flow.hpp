#pragma once
// The flow whose periodic orbits `lgi periodic` seeks, in a state x ∈ ℝ⁶
// (experiments/PERIODIC.md):
// - a heavy top: x = (Π, Γ), the Euler–Poisson flow (euler_poisson_flow.hpp);
//   its invariants H, Π·Γ = ℓ and |Γ|² = 1;
// - a Cardan top whose outer angle q1 is cyclic (vertical outer axis, or no
//   gravity; docs/cardan.md §9): x = (q, p) ∈ T³ × ℝ³, reduced at p1 = ℓ. Its
//   field does not depend on q1 and p1 is constant, so the flow of
//   (q2, q3, p2, p3) at p1 = ℓ is the reduced flow; q1 only drifts. The
//   reduced map keeps q1 where it started: φ̃_T(x) = φ_T(x) with q1 put back
//   (the drift is reported), and its field f̃ is f with the q1 component
//   zeroed. Then the reduced map has the same three "invariants" as the heavy
//   top's, in the same slots: H = h, p1 = ℓ and q1 = 0, and a periodic orbit
//   of φ̃ is a relative periodic orbit of the Cardan top (periodic up to a
//   turn of q1 by the drift). Its monodromy M̃ is M with the q1 row replaced
//   by e_q1ᵀ; M e_q1 = e_q1 (q1 cyclic) and e_p1ᵀ M = e_p1ᵀ make the q1 and
//   p1 multipliers exactly 1, and ∇Hᵀ M̃ = ∇Hᵀ, M̃ f̃ = f̃ hold as for the heavy
//   top (∂H/∂q1 = 0). The shape angles q2, q3 live on T²: a shot's end is
//   compared with a start modulo 2π in them (flow_difference), so an orbit
//   may wind in q2 or q3.
// The shots of a Cardan top integrate (x, X) with the T³ tangent flow
// (integrators/core/torus_tangent_flow.hpp): classical RK4 on the field and
// on its exact (dual-number) Jacobian, so the monodromy is the exact
// derivative of the discrete map. RK4 keeps p1 exactly (linear invariant) but
// H only to its error, O(dt⁴).
#include "experiments/analysis/periodic/euler_poisson_flow.hpp"
#include "integrators/system/cardan.hpp"

namespace lgi::experiments {

struct PeriodicFlow {
  HeavyTopBody body{};                         // a heavy top (cardan == nullptr)
  const system::CardanTop* cardan = nullptr;   // a Cardan top with a cyclic q1, not owned
  PeriodicFlow(const HeavyTopBody& b) : body(b) {}  // NOLINT: implicit, every heavy-top caller
  explicit PeriodicFlow(const system::CardanTop& top) : cardan(&top) {}
};

/// The field (f̃ for a Cardan top) and its Jacobian.
Vec6 flow_field(const PeriodicFlow& flow, const Vec6& x);
Mat6 flow_jacobian(const PeriodicFlow& flow, const Vec6& x);

/// The three invariants and their gradients: (H, Π·Γ, |Γ|²) or (H, p1, q1).
Invariants flow_invariants(const PeriodicFlow& flow, const Vec6& x);

/// Their values on the orbits sought at (h, ℓ): (h, ℓ, 1) or (h, ℓ, 0).
Eigen::Vector3d invariant_levels(const PeriodicFlow& flow, double h, double l);

/// end − start, the Cardan top's shape angles q2, q3 reduced to [−π, π).
Vec6 flow_difference(const PeriodicFlow& flow, const Vec6& end, const Vec6& start);

/// φ_T(x0) and its derivative in ⌈T/dt⌉ equal steps (Cardan: the reduced map
/// φ̃ of the top of this file, RK4; Shot::drift the turn of q1).
Shot shoot(const PeriodicFlow& flow, const Vec6& x0, double T, double dt);

/// One step of size h of the same map without the tangent flow.
bool flow_step(const PeriodicFlow& flow, Vec6& x, double h);

}  // namespace lgi::experiments
