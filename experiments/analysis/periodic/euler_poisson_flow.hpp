#pragma once
// The Euler–Poisson flow of a heavy top in x = (Π, Γ) ∈ ℝ⁶ and its tangent
// flow, for the shooting of `lgi periodic` (experiments/PERIODIC.md).
//
//   Π̇ = Π × Ω + Γ × w,  Γ̇ = Γ × Ω,  Ω = J⁻¹Π,  w = m g χ,
// with H = ½ Π·J⁻¹Π + w·Γ and the Casimirs C = Π·Γ, |Γ|² (docs/atlas.md §2).
//
// Integrator: the implicit midpoint rule composed twice by the triple jump
// (order 2 → 4 → 6; H. Yoshida, Phys. Lett. A 150 (1990) 262–268), nine
// midpoint substeps per step. Every substep keeps each quadratic first
// integral exactly (E. Hairer, C. Lubich, G. Wanner, Geometric Numerical
// Integration, 2nd ed., Thm. IV.2.1), and H, C, |Γ|² are all quadratic: so
// the discrete map keeps the level sets of all three, and the trivial Floquet
// multipliers are not split by integration error. The tangent flow is the
// exact derivative of the discrete map: X' = (I − h/2 A(m))⁻¹(I + h/2 A(m)) X,
// A the field's Jacobian at the substep's midpoint m.
// A shot over [0, T] takes N = ⌈T/dt⌉ equal steps, so it lands exactly on T.
// Its tangent flow is kept in pieces: a piece ends after the step at which
// its tangent flow's largest entry passes piece_growth, and the monodromy is
// the product of the pieces' (the same discrete map, the same steps). The
// multipliers are read from the pieces one by one (periodic_orbit.hpp,
// classify_orbit): on a strongly hyperbolic orbit the single product has
// entries of the size of its multiplier λ, and its small multiplier 1/λ and
// det P are lost to round-off amplified by λ² (K. Lust, Int. J. Bifurcation
// and Chaos 11 (2001) 2389–2410).
#include <Eigen/Core>
#include <vector>

#include "experiments/analysis/relative_equilibria.hpp"

namespace lgi::experiments {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

Vec6 euler_poisson_field(const HeavyTopBody& body, const Vec6& x);
Mat6 euler_poisson_jacobian(const HeavyTopBody& body, const Vec6& x);

/// H, C = Π·Γ and |Γ|², and their gradients (the rows of `gradients`).
struct Invariants {
  Eigen::Vector3d value;
  Eigen::Matrix<double, 3, 6> gradients;
};
Invariants euler_poisson_invariants(const HeavyTopBody& body, const Vec6& x);

/// A piece of a shot: from `start` to `end` with the tangent flow `monodromy`.
struct MonodromyPiece {
  Vec6 start, end;
  Mat6 monodromy;
};

/// A piece ends once its tangent flow's largest entry exceeds this (top of this file).
inline constexpr double piece_growth = 10.0;

struct Shot {
  Vec6 end;
  Mat6 monodromy;  // ∂(end)/∂(start): the product of the pieces' (last first)
  bool ok = true;  // false: a midpoint solve did not converge, the state is not finite, or a signal came
  double drift = 0.0;  // a Cardan top's turn of q1 over the shot (periodic_flow.hpp); 0 for a heavy top
  std::vector<MonodromyPiece> pieces{};  // in order along the shot; one when the tangent flow stays below piece_growth
};

/// Ends the shot's current piece (from `start` to s.end with tangent flow X): appends it,
/// restarts X at I and start at s.end.
void cut_piece(Shot& s, Vec6& start, Mat6& X);

/// The product of the pieces' tangent flows, the last first (I for none).
Mat6 pieces_product(const std::vector<MonodromyPiece>& pieces);

/// φ_T(x0) and its derivative, with ⌈T/dt⌉ equal sixth-order steps (top of this file).
/// Reads interrupt_requested (io/trajectory_observer.hpp) before every step and fails
/// (ok = false) once it is set: every Newton iteration and continuation step above then
/// fails at once, and lgi periodic drops the start in progress (experiments/PERIODIC.md).
Shot shoot(const HeavyTopBody& body, const Vec6& x0, double T, double dt);

/// One step of size h (h < 0: backwards) of the same map, without the tangent flow;
/// false if a midpoint solve failed or the state is not finite.
bool flow_step(const HeavyTopBody& body, Vec6& x, double h);

}  // namespace lgi::experiments
