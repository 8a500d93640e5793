#pragma once
// One periodic orbit of the Euler–Poisson flow in (Π, Γ) ∈ ℝ⁶ at fixed ℓ, by
// single shooting with Newton's method (or multiple shooting,
// ShootingSettings::shooting_points, multiple_shooting.hpp), and its Floquet multipliers
// (experiments/PERIODIC.md; R. Seydel, Practical Bifurcation and Stability
// Analysis, 3rd ed. (2010), ch. 7).
//
// Unknowns z = (x0, T, p) ∈ ℝ⁸, p = h (ℓ fixed) or, with in_l, p = ℓ (h
// fixed); equations (eleven)
//   φ_T(x0) − x0 = 0,                    (6)
//   ⟨f(x_p), x0 − x_p⟩ = 0,              (phase: x0 on the hyperplane through the predictor x_p ⊥ the flow;
//                                          with a section, S(x0) = 0 instead: x0 on the Poincaré section)
//   H(x0) = h, Π·Γ = ℓ, |Γ|² = 1,
//   ⟨t, z − z_p⟩ = 0                     (continuation: t = e_h fixes h; t the family's tangent is
//                                          pseudo-arclength, H. B. Keller (1977), Seydel §4.4).
// The monodromy M = ∂φ_T/∂x0 has four multipliers at 1 (flow, H and the two
// Casimirs), so φ_T − x0 alone is singular; the full system has rank 8 at an
// isolated orbit that is a regular point of its family. Each Newton step is
// the minimum-norm least-squares solution (complete orthogonal decomposition,
// rank threshold 1e-9 relative).
// Degenerate: the system's smallest singular value is below 1e-7 of the
// largest and all six multipliers are within 1e-5 of 1: the orbit lies in a
// continuum of periodic orbits at the same (h, ℓ), a resonant torus of an
// integrable top, and is not isolated.
#include <array>
#include <cmath>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "experiments/analysis/periodic/periodic_flow.hpp"
#include "experiments/analysis/periodic/section_crossings.hpp"

namespace lgi::experiments {

/// A point of a family in the unknowns of the corrector: (x0, T, p), p = h or ℓ.
using FamilyPoint = Eigen::Matrix<double, 8, 1>;

struct ShootingSettings {
  double dt = 2e-3;          // the step bound; a shot takes ⌈T/dt⌉ equal steps
  double tolerance = 1e-10;  // on the residual (below)
  int max_iterations = 30;
  std::optional<PhaseSection> section{};  // the phase condition S(x0) = 0 instead of the hyperplane
  bool in_l = false;                      // the eighth unknown is ℓ (at fixed h), not h (at fixed ℓ)
  int shooting_points = 1;                // M: 1 is single shooting, M > 1 multiple shooting (multiple_shooting.hpp)
};

struct PeriodicOrbit {
  Vec6 x0 = Vec6::Zero();  // (Π, Γ): a point of the orbit
  double period = 0.0, h = 0.0, l = 0.0;
  double residual = INFINITY;  // max(|φ_T(x0) − x0|, |H − h|, |Π·Γ − ℓ|, ||Γ|² − 1|, both plane conditions); ∞: no iterate

  Mat6 monodromy = Mat6::Identity();
  std::array<std::complex<double>, 6> multipliers{};  // the four trivial ones first, then the nontrivial pair
  std::string stability;   // elliptic, hyperbolic or inverse_hyperbolic (of the nontrivial pair)
  double reduced_trace = 0.0;      // trace of the monodromy on the section in the level set (below)
  Eigen::Matrix<double, 6, 2> section_basis = Eigen::Matrix<double, 6, 2>::Zero();  // that section's basis
  Eigen::Matrix2d reduced_monodromy = Eigen::Matrix2d::Identity();
  double invariance_defect = 0.0;  // the entries that vanish exactly for the exact flow (below)
  double trivial_deviation = 0.0;  // max |μ − 1| over the four trivial multipliers
  double product_deviation = 0.0;  // |∏ μ − 1|
  double rank_ratio = 0.0;         // smallest / largest singular value of the Newton system
  Eigen::Matrix<double, 8, 1> tangent = Eigen::Matrix<double, 8, 1>::Zero();  // the family's unit tangent in (x0, T, h), either sense
  bool degenerate = false;
  bool converged = false;
  bool in_l = false;  // found with p = ℓ at fixed h (ShootingSettings::in_l)
  int iterations = 0;
  double drift = 0.0;  // a Cardan top's turn of q1 over one period (periodic_flow.hpp); 0 for a heavy top
  std::vector<MonodromyPiece> pieces{};  // the monodromy's factors, in order (euler_poisson_flow.hpp; classify_orbit)
};

/// The continued parameter p of the orbit (ℓ if in_l, else h) and the fixed one.
inline double parameter_of(const PeriodicOrbit& o) { return o.in_l ? o.l : o.h; }
inline double fixed_of(const PeriodicOrbit& o) { return o.in_l ? o.h : o.l; }

/// Newton from (x_guess, T_guess) towards the orbit at (h, l); the phase
/// hyperplane passes through x_guess.
PeriodicOrbit correct_orbit(const PeriodicFlow& body, const Vec6& x_guess, double T_guess, double h, double l,
                            const ShootingSettings& s);

/// Newton from the predictor z_p with the continuation condition ⟨t, z − z_p⟩ = 0
/// (t need not be normalised; t = e_p is correct_orbit); `fixed` is ℓ, or h with s.in_l.
PeriodicOrbit correct_on_family(const PeriodicFlow& body, const FamilyPoint& z_p, const FamilyPoint& t, double fixed,
                                const ShootingSettings& s);

/// Newton's limit T → 0: φ_T(x0) = x0 holds for every x0 at T = 0, so a seed can converge to
/// that trivial solution (a residual at round-off, all multipliers 1). A period of at most one
/// step (s.dt) is that, never an orbit: such an iterate is not converged.
inline bool collapsed_to_zero_period(const PeriodicOrbit& o, const ShootingSettings& s) { return o.period <= s.dt; }

/// What a failed correction says: the trivial solution T → 0, or the residual Newton ended at.
std::string correction_failure(const PeriodicOrbit& o, const ShootingSettings& s);

/// (x0, T, p) of an orbit.
FamilyPoint family_point(const PeriodicOrbit& o);

/// The residual vector of the eleven equations at z = (x0, T, p) and their
/// Jacobian, given the shot φ_T(x0) and its monodromy (from one shot, or the
/// product of the segments' of multiple shooting); f_ref is the phase
/// hyperplane's normal (unused with a section).
struct CondensedSystem {
  Eigen::Matrix<double, 11, 1> r;
  Eigen::Matrix<double, 11, 8> A;
};
CondensedSystem condensed_system(const PeriodicFlow& body, const FamilyPoint& z, const FamilyPoint& z_p,
                                 const FamilyPoint& t, const Vec6& f_ref, double fixed, const ShootingSettings& s,
                                 const Vec6& end, const Mat6& monodromy);

/// Newton's stop: well below the tolerance, or at it once round-off dominates
/// (no tenfold gain left), or when it stalls, or at the iteration limit.
inline bool newton_done(int it, double res, double previous, const ShootingSettings& s) {
  return res <= s.tolerance * 1e-2 || (res <= s.tolerance && res > 0.1 * previous) || (it > 8 && res > 0.5 * previous) ||
         it == s.max_iterations;
}

/// Records the iterate z of a corrector as the orbit's best: x0, T, p, the
/// residual, the monodromy, rank_ratio and the family's tangent (from A).
void record_iterate(PeriodicOrbit& o, const FamilyPoint& z, double residual, const Mat6& monodromy,
                    const Eigen::Matrix<double, 11, 8>& A);

/// Multipliers, their checks, the stability class and the degeneracy of a corrected orbit
/// (floquet_multipliers.cpp).
///
/// The multipliers are read in an orthonormal basis adapted to what the exact
/// flow keeps: (n₁, n₂, n₃) spanning the gradients of H, Π·Γ and |Γ|² (a
/// Cardan top: H, p1, q1), then f̂ (the flow), then (w₁, w₂) completing the
/// tangent space of the level set. Each piece M_k of the monodromy (from x_k
/// to e_k; one piece, or several when the tangent flow grows: Shot::pieces,
/// and one or more a segment of multiple shooting) is written
/// B_k = Q(e_k)ᵀ M_k Q(x_k), block triangular for the exact flow,
///   B_k = [N_k 0; * C_k],  C_k = [1 *; 0 P_k],
/// since ∇I(e_k)ᵀ M_k = ∇I(x_k)ᵀ for each invariant I and M_k f(x_k) = f(e_k).
/// The diagonal blocks of the product are the products of the pieces' blocks:
/// the trivial multipliers are eig(∏N_k) and ∏(C_k)_ff, the nontrivial pair the
/// roots of μ² − tr P μ + det P with P = ∏P_k (the monodromy of the section in
/// the level set, Seydel §7.4) and det P = ∏ det P_k. Taking them from the
/// diagonal blocks is a conditioning choice, not a renormalisation: the
/// eigenvalue of a Jordan block moves by √ε under a perturbation ε, a diagonal
/// entry by ε; and a piece's blocks have entries of the size of its own growth
/// (≤ piece_growth), not of λ, so the small multiplier 1/λ and det P keep their
/// relative accuracy (K. Lust, Int. J. Bifurcation and Chaos 11 (2001) 2389).
/// The entries taken as zero are reported as `invariance_defect` (their
/// largest magnitude over the pieces).
void classify_orbit(const PeriodicFlow& body, PeriodicOrbit& o);

}  // namespace lgi::experiments
