#pragma once
// Relative equilibria of the Cardan-suspended top with a vertical outer axis
// (docs/cardan.md §9; the model: integrators/system/cardan.hpp).
//
// With α = 0 (or without gravity) the outer angle q1 is cyclic and p1 = ℓ is an integral.
// Routh's reduction (J. E. Marsden, Lectures on Mechanics, LMS Lecture Note
// Series 174, CUP 1992, §3–§4: the amended and the augmented potential)
// leaves the shape r = (q2, q3) ∈ T² with the amended potential
//   U_ℓ(r) = V(r) + ℓ² / (2 M₁₁(r)),
// M₁₁ the locked inertia of the whole mechanism about the outer axis
// (body and rings turning together). A relative equilibrium (the mechanism
// turning rigidly about the vertical, q̇ = (ω, 0, 0)) is a critical point of
// U_ℓ, with ω = ℓ/M₁₁ and energy h = U_ℓ. Equivalently, at fixed ω, a
// critical point of the augmented potential W_ω(r) = V(r) − ½ω² M₁₁(r);
// then ℓ = ω M₁₁ and h = V + ½ω² M₁₁. With massless rings, M₁₁ = Γ·JΓ and
// U_ℓ is the SO(3) amended potential of docs/atlas.md §3 in the chart
// Γ = (s2 s3, s2 c3, c2): the equilibria are Staude's permanent rotations.
//
// Stability: the reduced system in (q2, q3, p2, p3) at p1 = ℓ is canonical;
// its 4×4 linearisation A at the equilibrium has det(λ − A) = λ⁴ + g1 λ² + g2
// with g1 = −½ tr A², g2 = det A, and the class follows from (g1, g2) as for
// Grammel's coefficients on SO(3) (docs/atlas.md §3). Nonlinear stability:
// a strict minimum of U_ℓ (positive-definite Hessian) is Lyapunov stable
// for the reduced system (energy–momentum method, Marsden op. cit. §5).
//
// Degenerate families: where the Hessian of U_ℓ has a zero eigenvalue along
// q3 the equilibrium is a circle of them (the Lagrange top, whose q3 is
// cyclic too, and the poles sin q2 = 0, where body and outer axis coincide
// and q1, q3 turn about the same axis). Such a circle is reported once, at
// q3 = 0, with `degenerate` set.
#include <cstddef>
#include <functional>
#include <vector>

#include "experiments/analysis/relative_equilibria.hpp"
#include "integrators/system/cardan.hpp"

namespace lgi::experiments {

/// An angle reduced to (−π, π] and to [0, 2π).
double wrap_angle_signed(double a);
double wrap_angle_positive(double a);

struct CardanEquilibrium {
  Vec3 q = Vec3::Zero();                 // (0, q2, q3), q2 in (−π, π], q3 in [0, 2π)
  double omega = 0.0, l = 0.0, h = 0.0;  // q̇1, p1, H
  Vec3 gamma = Vec3::Zero();             // the vertical in the body frame, R(q)ᵀ e3
  Vec3 angular_momentum = Vec3::Zero();  // the body's Π = J E(q) q̇
  int branch = 0;
  double g1 = 0.0, g2 = 0.0;
  EquilibriumStability stability = EquilibriumStability::stable;
  bool nonlinearly_stable = false;
  bool degenerate = false;  // a circle of equilibria in q3
  bool pole = false;        // sin q2 = 0: the body's axis on the outer axis (gimbal lock without ring inertia)
  double residual = 0.0;    // |∇U| at the polished point
};

/// Throws InputError unless q1 is cyclic (tilt 0, or no gravity: CardanTop::outer_angle_cyclic).
void require_cyclic_outer_angle(const system::CardanTop& top, const std::string& file, const std::string& command);

/// Every relative equilibrium at p1 = l: the critical points of U_l on T²,
/// found from a grid of `grid` × `grid` cells and polished by Newton.
std::vector<CardanEquilibrium> cardan_equilibria_at(const system::CardanTop& top, double l, int grid = 96);

/// The bifurcation diagram: the critical points of W_ω for `samples` values
/// of ω in [−omega_max, omega_max], joined into branches by continuation
/// (`branch`: the same id along a branch). `sample_done`, if given, is called
/// after each ω with the values done and their number; false stops there (a
/// signal), with the rows so far.
std::vector<CardanEquilibrium> cardan_equilibrium_branches(
    const system::CardanTop& top, int samples, double omega_max, int grid = 64,
    const std::function<bool(std::size_t, std::size_t)>& sample_done = {});

/// A default ω range for the diagram: 3 √(|∇V|_max / min M₁₁), or 3 without a potential.
double default_cardan_omega_max(const system::CardanTop& top);

/// The least value of U_l on the slice q1 = 0 (for a vertical axis, the
/// least energy at p1 = l): the lowest critical point, checked on a grid.
double cardan_minimum_energy(const system::CardanTop& top, double l);

/// U_l(q2, q3) on the slice q1 = 0.
double cardan_amended_potential(const system::CardanTop& top, double l, double q2, double q3);

}  // namespace lgi::experiments
