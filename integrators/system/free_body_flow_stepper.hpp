#pragma once
// The exact free-rigid-body flow as a STEPPER: (R, Π) ↦ Φ_h(R, Π) from an
// arbitrary state, for the free part of the Strang splitting `split-exact`
// (integrators/schemes/splitting.hpp), which re-starts the free flow after every kick.
//
// FreeBodyExactFlow (free_body_exact.hpp) is built for one
// initial state and many output times: its constructor sorts the inertia,
// computes K, u0 = F(φ0), the complete integral Zc and the AGM table, and its
// at(t) evaluates one more R_J. Re-constructing it every step costs 2 R_F and
// 3 R_J calls. This class keeps the same formulas (and the same working
// frames, notation and references: see free_body_exact.hpp) but splits the
// work by what it depends on:
//   per run (constructor): the principal frame P sorted ascending, the two
//     working frames (Δ > 0 and Δ < 0) with their signed differences Iij,
//     the characteristic n = −I3 I21/(I1 I32) and every ratio of moments;
//     the regime of the inertia (spherical / two equal moments / asymmetric).
//   per step (advance): G, 2T, Δ (double-double, free_body_special.cpp),
//     amplitudes a1, b, a3, λ, k², k'²; the AGM table for k (5–7 square
//     roots; it also gives K = π/(2 a_N), so no R_F is needed); and
//       Π:  the phase u0 is never formed. (cn, sn, dn)(u0) = (Π1/a1, Π2/b, Π3/a3)
//           are read off the state, (sn, cn, dn)(λh) come from the AGM, and the
//           addition theorem (DLMF 22.8.1–3)
//             sn(u+v) = (s1 c2 d2 + s2 c1 d1)/D,  cn(u+v) = (c1 c2 − s1 d1 s2 d2)/D,
//             dn(u+v) = (d1 d2 − k² s1 c1 s2 c2)/D,  D = 1 − k² s1² s2²
//           gives Π at u0 + λh. (Absolute accuracy ~ε|Π|; cancellation near a
//           zero of cn or a minimum of dn costs relative, not absolute, digits.)
//       R:  the increment of the precession angle over the step,
//             Δψ = (G/I1) h + c_Π [Z(u1) − Z(u0)],  Z(u) = ∫₀^u n sn²w/(1 − n sn²w) dw
//           (free_body_exact.hpp writes Z(am u) = (n/3) sin³φ R_J(cos²φ, 1 − k² sin²φ,
//           1, 1 − n sin²φ), DLMF 19.25.14, continued quasi-periodically through ±K).
//           The difference comes from Jacobi's addition theorem for the integral
//           of the third kind, Π(u, a) in Jacobi's notation (Whittaker & Watson,
//           A Course of Modern Analysis, ch. XXII; here with n = k² sn²a),
//             Z(u) + Z(v) − Z(u + v) = (sn a/(cn a dn a)) ½ ln[(1 − k² sn a sn u sn v sn(u+v−a))
//                                                        /(1 + k² sn a sn u sn v sn(u+v+a))],
//           made real for n < 0 (a imaginary; derived here and checked to 1e-24
//           with mpmath on random k², n ∈ [−1e3, −1e-2], |v| ≤ K/2):
//             Z(u1) − Z(u0) = Z(v) − (−n/ρ) atan2(ρ s0 sv s1, 1 − n s1² + n s0 sv c1 d1),
//             ρ = √(−n (k² − n)(1 − n))
//           (the atan2 argument never crosses the negative axis: its first
//           component vanishes only where the second is positive). So one R_J per
//           step, for Z(v) at the small phase v = λh, where its arguments are
//           nearly equal and Carlson's duplication is cheap; no crossing of ±K
//           needs the complete integral. Then
//             R_{n+1} = R_n Q_w B(Π_w0)ᵀ Rz(Δψ) B(Π_w1) Q_wᵀ,  Π_{n+1} = Q_w Π_w1,
//           which is free_body_exact.hpp's R(t) = L Rz(ψ) B(Π_w(t)) Qᵀ with L
//           taken at the start of the step.
//     Steps with λ|h| > K/2 (more than an eighth of Π's period; only for very
//     coarse steps) take a general path: u0 = F(φ0) (one R_F), u1 = u0 + λh
//     reduced mod 2K, Jacobi functions at u1 directly, Z at both ends and the
//     complete Zc (three R_J).
//   separatrix (Δ = 0 exactly): sn = tanh, cn = dn = sech, and the closed form
//     Π(n; gd u, 1) of free_body_exact.hpp; no special functions.
//   two equal moments (per run): Π(h) = exp(−νh d̂)Π, R(h) = R exp(hΠ̂/A) exp(νh d̂),
//     ν = (1/C − 1/A) Π·d: two Rodrigues rotations, no elliptic functions.
//   spherical (per run): R exp(hΠ/I).
//   steady (per step, two principal components exactly 0): R exp(h G/I_i Π̂/G).
// No allocation; nothing is cached between steps (the state changes between
// them in a splitting), so advance() is const and re-entrant.
#include "integrators/system/inertia.hpp"
#include "lie/product_state.hpp"

namespace lgi::system {

class FreeBodyFlowStepper {
 public:
  enum class Shape { spherical, symmetric, asymmetric };

  FreeBodyFlowStepper() = default;
  /// Per-run set-up: everything that depends only on the inertia.
  explicit FreeBodyFlowStepper(const Inertia& inertia);

  /// Advances (R, Π) by the exact free flow over h (either sign). No allocation.
  void advance(lie::SO3xR3& s, double h) const;

  Shape shape() const { return shape_; }

 private:
  // One of the two working frames of free_body_exact.hpp (Δ > 0: moments
  // ascending; Δ < 0: reversed), with the ratios the per-step formulas use.
  struct Frame {
    lie::Mat3 Q[2];           // x_body = Q x_w; [1]: rotated by π about the first axis (Π3 > 0)
    double I1 = 1, I2 = 1, I3 = 1;
    double I21 = 0, I31 = 0, I32 = 0;
    double c13_1 = 0, c13_2 = 0;  // C13 = Π1² c13_1 + Π2² c13_2 (I31/I1, I32/I2)
    double c31_2 = 0, c31_3 = 0;  // C31 = Π2² c31_2 + Π3² c31_3 (I21/I2, I31/I3)
    double a1_sq = 0, a3_sq = 0;  // a1² = C13 a1_sq, a3² = C31 a3_sq (I1/I31, I3/I31)
    double lambda_sq = 0;         // λ² = C31 lambda_sq (I32/(I1 I2 I3))
    double b_coef = 0;            // b = a1 a3 b_coef/λ (I31/(I1 I3))
    double k2_coef = 0;           // k² = (C13/C31) k2_coef (I21/I32)
    double kc2_coef = 0;          // k'² = (Δ/C31) kc2_coef (I31/I32)
    double n = 0, n_third = 0;    // characteristic −I3 I21/(I1 I32) and n/3
    double minus_n = 0, one_minus_n = 1;
    double cpi_coef = 0;          // c_Π = G cpi_coef/λ (I31/(I1 I3))
    double sep_root = 0, sep_coef = 0;  // √(−n), √(−n)/(1 − n)
  };

  void advance_asymmetric(lie::SO3xR3& s, double h) const;

  Shape shape_ = Shape::spherical;
  lie::Vec3 I_ = lie::Vec3::Ones();      // principal moments, ascending
  lie::Mat3 P_ = lie::Mat3::Identity();  // x_body = P x_principal, det +1
  // two equal moments A, distinct C about the body unit axis d
  double sym_A_ = 1.0, sym_C_ = 1.0;
  lie::Vec3 sym_axis_ = lie::Vec3::UnitZ();
  Frame frame_[2];  // [0]: Δ ≥ 0, [1]: Δ < 0
};

}  // namespace lgi::system
