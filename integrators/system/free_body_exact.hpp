#pragma once
// The exact flow of the free rigid body (scheme `exact`, and the free part of
// the Strang splitting of docs/math.md §7, "Splitting with the exact free flow").
//
// Conventions (docs/conventions.md): Ṙ = R Ω̂, Π = JΩ, Π̇ = Π × Ω, R maps body
// to space, m = RΠ is constant. Invariants: |Π| = G, 2T = Π·J⁻¹Π, m.
//
// ── Frames ───────────────────────────────────────────────────────────────────
// J = P diag(principal) Pᵀ. The constructor sorts the principal moments (Inertia
// keeps a diagonal J's moments in the given order) and
// picks a constant "working" frame x_body = Q x_w (Q ∈ SO(3), a signed
// permutation of P's columns) with moments (I1, I2, I3), I2 the middle one,
// in which Π3 > 0 at t = 0 and the dn-component is Π3 (so Π3 never changes
// sign):
//   Δ := G² − 2T I2 > 0 (rotation about the largest axis):  (I1,I2,I3) ascending,
//   Δ < 0 (rotation about the smallest axis):            (I1,I2,I3) = the
//       ascending moments reversed, Q = P·[e3, −e2, e1] (a proper rotation).
// Every formula below is written with signed differences Iij = Ii − Ij, so it
// holds for both orderings (all of I21, I31, I32 have the sign of I31).
// The working-frame state is (R_w, Π_w) = (R Q, Qᵀ Π); Euler's equations keep
// their form.
//
// ── Π(t) (Celledoni et al. 2008, §2, cases (i)/(ii); with the sign of λ
//    corrected by P. Leroy, Principia documentation/Celledoni.tex,
//    "Solution of Euler's equation", eqs. (solneuleri)/(solneulerii)) ─────────
// With the cancellation-free forms (Celledoni.tex, "The quantity Δj")
//   C13 := 2T I3 − G² = Π1² I31/I1 + Π2² I32/I2,
//   C31 := G² − 2T I1 = Π2² I21/I2 + Π3² I31/I3,
//   Δ   := G² − 2T I2 = −Π1² I21/I1 + Π3² I32/I3,
// the solution is
//   Π1 = a1 cn(u, k),  Π2 = b sn(u, k),  Π3 = a3 dn(u, k),   u = λ t + u0,
//   a1² = C13 I1/I31,  a3² = C31 I3/I31,  λ² = I32 C31/(I1 I2 I3),
//   b = a1 a3 I31/(I1 I3 λ),  k² = I21 C13/(I32 C31),  k'² = 1 − k² = I31 Δ/(I32 C31).
// (Substituting into Π̇1 = Π2Π3 I23/(I2I3), Π̇2 = Π3Π1 I31/(I3I1),
//  Π̇3 = Π1Π2 I12/(I1I2) with DLMF 22.13.1–3 checks all three; k'² is
//  Celledoni.tex's m_c = Δ2 I31/(Δ1 I32) of its case (ii), from Δ without forming
//  1 − k².) a1 carries the sign of Π1(0), so cn(u0) ≥ 0 and u0 ∈ [−K, K]:
//   u0 = F(φ0, k) = sin φ0 R_F(cos²φ0, 1 − k² sin²φ0, 1),  φ0 = atan2(Π2/b, Π1/a1)
//   (DLMF 19.25.5 with its arguments scaled by sin²φ0: R_F is homogeneous of
//   degree −1/2, R_J of degree −3/2).
// Separatrix (Δ = 0, k = 1, the homoclinic orbit; Celledoni.tex case (iii)
// with its two free signs, here the signs of a1 and a3): sn = tanh,
// cn = dn = sech (DLMF 22.5(ii)), u0 = asinh(sn/cn).
// Period of Π: 4K/λ, K = R_F(0, k'², 1) (DLMF 19.25.1).
//
// ── R(t) ────────────────────────────────────────────────────────────────────
// Euler angles ZXZ (docs/conventions.md §2) about the constant m: with S ∈ SO(3)
// constant, S e3 = m/G,
//   R_w(t) = S Rz(ψ(t)) B(Π_w(t)),   B = Rx(θ) Rz(φ),
//   cos θ = Π3/G, sin θ = √(Π1² + Π2²)/G ∈ (0, 1], (sin φ, cos φ) ∝ (Π1, Π2),
// so that Bᵀ e3 = Π_w/G (third row of B) and R_w Π_w = G S e3 = m.
// B is smooth because Π3 > 0 keeps θ < π/2 and (Π1, Π2) ≠ 0 off the steady
// rotations (handled apart). The precession rate is the one of
// Landau & Lifshitz, Mechanics, §37 (docs/conventions.md §2, inverse chart map):
//   ψ̇ = (Ω1 sin φ + Ω2 cos φ)/sin θ = G (Π1²/I1 + Π2²/I2)/(Π1² + Π2²)
//      = G/I3 + (G C13/(I3 a1²)) / (1 − n sn²u),   n = −I3 I21/(I1 I32) < 0,
// integrated with the incomplete integral of the third kind
// (Π(n; φ, k) = ∫₀^φ dθ/((1 − n sin²θ)√(1 − k² sin²θ)), Boost's convention):
//   ψ(t) = (G/I3) t + c_Π [Π(n; am u, k) − Π(n; am u0, k)],  c_Π = G I31/(λ I1 I3).
// This is Celledoni.tex, "Integrals/Case (ii)", whose characteristic
// I3 I21/(I1 I23) and coefficient G I31/(λ I1 I3) are the same; its extra
// arctan(sc) term belongs to its different (minimal-rotation quaternion) choice
// of B and is absent here. (Celledoni.tex notes that the paper's value of n in
// ψ(t) is wrong and corrects the sign of its f(s); neither is used here.)
// Evaluation without loss over many periods: with Π(n; φ) = F(φ) + Z(φ),
//   Z(φ) = (n/3) sin³φ R_J(cos²φ, 1 − k² sin²φ, 1, 1 − n sin²φ)  (DLMF 19.25.14
//   scaled by homogeneity; no cancellation since n < 0),
// and am(u + 2Kj) = am(u) + jπ (DLMF 22.16.2), reduce u = 2K j + r, |r| ≤ K:
//   Π(n; am u) = u + 2j Zc + Z(am r),  Zc = Π(n) − K = (n/3) R_J(0, k'², 1, 1 − n),
//   ψ(t) = (G/I1) t + c_Π [2j Zc + Z(am r) − Z(am u0)]     (G/I3 + c_Π λ = G/I1).
// On the separatrix Π(n; gd u, 1) = [u + √(−n) atan(√(−n) tanh u)]/(1 − n), so
//   ψ(t) = (G/I2) t + c_Π √(−n)/(1 − n) [atan(√(−n) tanh u) − atan(√(−n) tanh u0)].
// Back to the body: R(t) = L Rz(ψ) B(Π_w(t)) Qᵀ with L = R(0) Q B(Π_w(0))ᵀ,
// Π(t) = Q Π_w(t).
//
// ── Numerics ─────────────────────────────────────────────────────────────────
// * k' is formed from Δ, never as √(1 − k²); Δ I1 I3 = Π3² I32 I1 − Π1² I21 I3 is
//   evaluated in double-double (its terms cancel near the separatrix planes,
//   and δΔ/Δ becomes δK/K ~ the long-time phase error).
// * sn, cn, dn: own evaluation by the descending Gauss transformation along the
//   AGM chain a0 = 1, b0 = k' (DLMF 22.7.1–3, 22.20(ii)), in the rational
//   (Bulirsch 1965) form with y = sn/cn: every step multiplies, divides or adds
//   positive numbers, so the values keep full relative accuracy as k → 1, where
//   the arcsine recurrence of A&S 16.4 loses digits and Boost's jacobi_elliptic
//   (which takes k, not k') loses k'. For |r| > K/2 the quarter-period shift
//   (DLMF Table 22.4.3) sn(K − v) = cd v, cn(K − v) = k' sd v, dn(K − v) = k' nd v
//   keeps cn and dn relatively accurate near their minima.
// * R_F, R_J: Boost.Math (Carlson's duplication algorithm), in double.
// * A non-diagonal J is decomposed again in long double (its moments then carry
//   only their final rounding; the precession angle G t/I1 accumulates any error
//   of I1).
// * Accuracy is set by the phases: errors of a few ulps of the elliptic phase
//   λ t and of the precession angle ψ(t) (10⁴ rad after 100 periods of the
//   prism scene) are the floor of any double evaluation at absolute time t.
//
// ── Regimes ──────────────────────────────────────────────────────────────────
//   rest        Π = 0: R, Π constant.
//   spherical   I1 = I3: R(t) = R0 exp(t Π̂0/I), Π constant.
//   symmetric   two equal moments A (exactly), distinct C about unit body axis d:
//               Π(t) = exp(−νt d̂) Π0, R(t) = R0 exp(t Π̂0/A) exp(νt d̂),
//               ν = (1/C − 1/A) Π0·d  (check: Ω = Π/A + ν d, Π̇ = Π × ν d).
//   steady      Π0 along a principal axis (two principal components exactly 0):
//               R(t) = R0 exp(t G/I_i (Π0/G)^), Π constant (covers the middle axis,
//               the saddle of the separatrix).
//   elliptic    Δ ≠ 0: the formulas above (cases (i)/(ii) of Celledoni et al.).
//   separatrix  Δ = 0 exactly, as computed (also k'² below the smallest normal
//               double). No tolerance: a Δ off by rounding is the exact flow of
//               an elliptic orbit ulps away, and the elliptic formulas join the
//               hyperbolic ones continuously as k' → 0.
//
// References
//   E. Celledoni, F. Fassò, N. Säfström, A. Zanna, The exact computation of the
//     free rigid body motion and its use in splitting methods, SIAM J. Sci.
//     Comput. 30 (2008) 2084–2112 (§2: Π(t) in its cases (i)–(iii); §3: R(t)).
//   P. Leroy, On an article by Celledoni et al., mockingbirdnest/Principia,
//     documentation/Celledoni.tex (sign of λ, k'², the separatrix, Π-integral).
//   L. D. Landau, E. M. Lifshitz, Mechanics, 3rd ed., §37 (Euler angles about M).
//   NIST DLMF §19.16, §19.25 (Carlson forms), §22.4, §22.5, §22.7, §22.13, §22.16,
//     §22.20.
//   R. Bulirsch, Numerical calculation of elliptic integrals and elliptic
//     functions, Numer. Math. 7 (1965) 78–90 (sn, cn, dn from k' by Gauss steps).
//   M. Abramowitz, I. Stegun, Handbook of Mathematical Functions, 16.4.
// (No code was taken from these; Principia's physics/euler_solver.hpp was not copied.)
#include <limits>

#include "integrators/system/free_body_special.hpp"
#include "integrators/system/inertia.hpp"
#include "lie/product_state.hpp"

namespace lgi::system {

class FreeBodyExactFlow {
 public:
  enum class Regime { rest, spherical, symmetric, steady, elliptic, separatrix };

  // Per-run set-up: everything that depends only on the inertia and the initial state
  // (principal frame, regime, elliptic modulus, periods, constants of the attitude formula) is computed here.
  FreeBodyExactFlow(const Inertia& inertia, const lie::SO3xR3& initial);
  // The exact state at time t (absolute time since the initial state). No allocation.
  lie::SO3xR3 at(double t) const;

  Regime regime() const { return regime_; }
  /// The period of Π(t): 4K/λ (elliptic), 2π/|ν| (symmetric); +∞ where Π is
  /// constant or on the separatrix.
  double momentum_period() const { return momentum_period_; }
  /// k'² = 1 − k² (elliptic: in (0, 1]; separatrix: 0; otherwise 1).
  double complementary_parameter() const { return kc2_; }

 private:
  // Π_w and the non-linear part of ψ at phase u (elliptic or separatrix).
  void momentum_and_angle(double u, lie::Vec3& pi_w, double& z) const;

  Regime regime_ = Regime::rest;
  lie::SO3xR3 initial_;
  double momentum_period_ = std::numeric_limits<double>::infinity();
  double kc2_ = 1.0;

  // spherical / steady / symmetric
  lie::Vec3 axis_ = lie::Vec3::UnitZ();     // unit Π0 direction
  double axis_rate_ = 0.0;                  // G/I (angular rate about axis_)
  lie::Vec3 sym_axis_ = lie::Vec3::UnitZ(); // d (body)
  double nu_ = 0.0;

  // elliptic / separatrix
  lie::Mat3 Q_ = lie::Mat3::Identity();   // x_body = Q x_w
  lie::Mat3 L_ = lie::Mat3::Identity();   // R(0) Q B(Π_w(0))ᵀ
  double a1_ = 0.0, b_ = 0.0, a3_ = 0.0;  // amplitudes
  double lambda_ = 0.0, u0_ = 0.0;
  double k2_ = 0.0, kc_ = 1.0;            // k², k'
  double K_ = 0.0;
  double n_ = 0.0, n_third_ = 0.0, two_zc_ = 0.0;  // characteristic, n/3, 2(Π(n) − K)
  double psi_rate_ = 0.0, c_pi_ = 0.0, z0_ = 0.0;   // ψ = psi_rate t + c_pi (Z − Z0)
  double sep_root_ = 0.0;                 // √(−n) (separatrix)
  free_body_detail::Agm agm_;             // AGM table for the Jacobi functions of k
};

}  // namespace lgi::system
