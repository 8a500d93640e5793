#pragma once
// Implicit Runge–Kutta–Munthe-Kaas on SO(3) × ℝ³ over the collocation
// tableaus of tableaus/implicit.hpp: rkmk-gauss2, rkmk-gauss4 (symmetric,
// A-stable) and rkmk-radau5 (L-stable, stiffly accurate).
//
// RKMK (Munthe-Kaas, Appl. Numer. Math. 29 (1999) 115–127, Algorithm 1;
// Iserles, Munthe-Kaas, Nørsett & Zanna, Acta Numerica 9 (2000), §5.3,
// eq. (5.14)) with a fully implicit tableau (a, b, c), body form (docs/math.md §9):
// the unknowns are the stage increments Z_i = (w_i, δΠ_i) ∈ so(3) × ℝ³,
//   w_i = h Σ_j a_ij k̃_j,   δΠ_i = h Σ_j a_ij K_j,
//   R_i = R̄ exp(u_i),  Π_i = Π_n + δΠ_i,  Ω_i = J⁻¹Π_i,
//   k̃_i = dexp⁻¹_body(u_i) Ω_i,   K_i = Π_i × Ω_i + τ(R_i, Π_i, t_n + c_i h),
// and the step is  R_{n+1} = R_n exp(Θ),  Π_{n+1} = Π_n + Σ_i d_i δΠ_i,
//   Θ = h Σ_i b_i k̃_i = Σ_i d_i w_i   (d = bᵀA⁻¹; HW II §IV.8, eq. (8.2b)).
// Chart centre:
//  - plain RKMK (radau5): R̄ = R_n, u_i = w_i (the chart at the step start);
//  - centred RKMK (gauss2, gauss4): R̄ = R_n exp(Θ/2), u_i = w_i − Θ/2, the
//    chart at the step's midpoint: the same collocation method applied to
//    u̇ = dexp⁻¹_body(u) Ω in one fixed chart around R̄, from u = −Θ/2 to
//    u = +Θ/2. This is the symmetric method based on local coordinates of
//    Hairer, GNI (Hairer, Lubich & Wanner 2006) §V.4.1 and BIT 41 (2001)
//    996–1007, §4 (chart chosen so that z_n = −z_{n+1}), and the
//    self-adjoint RKMK of Zanna, Engø & Munthe-Kaas, "Adjoint and
//    selfadjoint Lie-group methods", BIT 41 (2001) 395–421 (see also
//    Iserles et al. 2000, §7). A step back from R_{n+1} with −h finds the
//    same R̄, so a symmetric tableau gives a symmetric method. With the chart
//    at R_n, RKMK-Gauss4 is NOT symmetric (the change between the charts at
//    R_n and R_{n+1} is nonlinear; measured Φ₋ₕ∘Φₕ − id = 2.4e-10 at h = 0.1
//    on free_body_hlw, against 1e-16 centred; tests/test_implicit.cpp).
//    For s = 1 both charts give the same method (u_1 = 0, and w_1 ∥ Ω_1 in
//    the chart at R_n). Centring also halves the largest chart coordinate
//    (|u_i| ≲ |Θ|/2), so the midpoint rule never meets the 2π singularity.
// Order: that of the tableau (2, 4, 5): dexp⁻¹ is exact, and in a fixed
// chart the method is the collocation method itself (Munthe-Kaas 1999,
// Theorem; Zanna et al. 2001 for the centred chart). Stability: the
// tableau's on the ℝ³ factor (Gauss A-stable; Radau IIA L-stable, and
// stiffly accurate: the step ends on the last stage).
// Conserves: RᵀR = I to round-off (R only moves by exp). For a free body
// the Π equation decouples (K does not depend on R) and RKMK applies the
// collocation method to it unchanged, so the Gauss schemes conserve its
// quadratic invariants |Π|² and Π·J⁻¹Π exactly (HLW, GNI, Theorem IV.2.1):
// measured drift over 1e5 steps ≤ 3e-14 at h = 0.01, ≤ 2e-12 at h = 0.3
// (round-off). Nothing else exactly: not m = RΠ, and with a torque not the
// energy (the attitude is not advanced by the collocation method itself).
// Not symplectic as a method on T*SO(3).
//
// Newton. The 6s equations G(Z) = Z − h (A ⊗ I₆) F(Z) = 0 are solved by
// Newton's method with the model's analytic Jacobian (rigid_body.hpp) and
// the exact derivative of dexp⁻¹ (dexpinv_body_derivative below), from
// Z = 0 (the first correction is then the linearly implicit, Rosenbrock-like
// predictor, which is what a stiff problem needs: an explicit predictor
// c_i h F(y_n) would overshoot by h·c/J ≈ 100 on the stiff scene).
// Full Newton (Jacobian and LU at every iterate) or simplified Newton
// (both frozen at Z = 0, i.e. at the step start): NewtonSettings::jacobian.
// The registry uses `refreshed`: simplified Newton that re-evaluates the
// Jacobian at the current iterate when the observed contraction
// θ_k = |ΔZ_k|/|ΔZ_{k−1}| exceeds 0.25 (in the spirit of Hairer & Wanner's
// RADAU5, HW II §IV.8, with a per-step instead of a per-run Jacobian).
// Why (measured, tests/test_implicit.cpp "[.bench]", min of 7 runs):
//  - at small steps all three variants need the same 3 iterations, and one
//    LU per step instead of three halves the cost (radau5 on
//    heavy_top_trindade_1 at h = 1e-3: 3.9 µs/step refreshed or simplified,
//    8.2 µs full);
//  - pure simplified Newton fails at large h|Ω| (heavy_top_trindade_1 at
//    h = 0.1, h|Ω| ≈ 5: radau5 does not converge in 30 iterations, gauss4
//    needs 28), where refreshing costs 8–10 iterations against full
//    Newton's 4–5 and is still 12–22 % cheaper than full Newton.
// Convergence is declared on the scaled max-norm of the Newton correction
// (angles relative to max(1 rad, |w_i|), momenta relative to
// max(|Π_n|, |Π_stage|)):
//   |ΔZ_k| ≤ tol, or (k ≥ 3) θ_k/(1 − θ_k) |ΔZ_k| ≤ tol (HW II §IV.8,
//   eq. (8.10)), or (k ≥ 3) round-off stagnation (θ_k ≥ ½ with
//   |ΔZ_k| ≤ 100 tol);  tol = 1e-15, a few units of round-off. With
//   1e-14 the Gauss schemes' conservation of |Π| and H for a free body
//   drifted by 1e-10 over 1e5 steps of h = 0.3 (the stage equations left
//   unsolved by ~1e-15 per step); with 1e-15 by 8e-13, as with 1e-16.
// The step fails (converged = false, with the iterations and the last
// correction norm as the "residual") after max_iterations, on non-finite
// values, or when a chart coordinate |u_i| exceeds 2π − ½ (dexp⁻¹ is
// singular at 2π, and beyond it Newton could converge to a spurious
// solution on another branch).
// No allocation: fixed-size Eigen types throughout (6s × 6s matrices).
#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "integrators/core/scheme_interface.hpp"
#include "integrators/tableaus/implicit.hpp"

namespace lgi::integrators {

namespace detail {

/// c'(s) = dc/d(θ²) for c(θ) = (1 − (θ/2) cot(θ/2))/θ² (so3.hpp).
/// Closed form −1/θ⁴ + cot(θ/2)/(4θ³) + 1/(8θ² sin²(θ/2)); below θ = 1,
/// where that cancels, the series Σ_{n≥2} (n−1) α_n s^(n−2) with
/// α_n = |B_2n|/(2n)! (c = Σ_{n≥1} α_n s^(n−1)); truncation < 1e-16·c'.
inline double dexpinv_coefficient_derivative(double theta2) {
  if (theta2 < 1.0) {
    constexpr double alpha[] = {
        0.0, 0.0,
        1.0 / 720.0,                // α2
        1.0 / 30240.0,              // α3
        1.0 / 1209600.0,            // α4
        1.0 / 47900160.0,           // α5
        5.2841901386874931848e-10,  // α6 = 691/1307674368000
        1.3382536530684678833e-11,  // α7 = 1/74724249600
        3.3896802963225828668e-13,  // α8
        8.5860620562778445641e-15,  // α9
        2.1748686985580618730e-16,  // α10
        5.5090028283602295152e-18,  // α11
    };
    double sum = 0.0;
    for (int n = 11; n >= 2; --n) sum = sum * theta2 + (n - 1) * alpha[n];
    return sum;
  }
  const double theta = std::sqrt(theta2);
  const double half = 0.5 * theta;
  const double sh = std::sin(half);
  return -1.0 / (theta2 * theta2) + std::cos(half) / sh / (4.0 * theta2 * theta) + 1.0 / (8.0 * theta2 * sh * sh);
}

/// ∂/∂u [dexp⁻¹_body(u) v] for fixed v, with dexp⁻¹_body(u) v = v + ½ u × v + c(|u|) u × (u × v):
///   −½ v̂ + 2 c'(|u|²) (u × (u × v)) uᵀ − c(|u|) ((u × v)^ + û v̂).
inline Mat3 dexpinv_body_derivative(const Vec3& u, const Vec3& v) {
  const double s = u.squaredNorm();
  const Vec3 uv = u.cross(v);
  const Mat3 U = lie::hat(u);
  return -0.5 * lie::hat(v) + (2.0 * dexpinv_coefficient_derivative(s)) * (u.cross(uv) * u.transpose()) -
         lie::detail::dexpinv_coefficient(s) * (lie::hat(uv) + U * lie::hat(v));
}

}  // namespace detail

enum class NewtonJacobian {
  full,        // Jacobian and LU at every iterate (quadratic convergence)
  simplified,  // frozen at the step start (linear convergence, one LU per step)
  refreshed,   // simplified, re-evaluated at the current iterate whenever θ_k > 0.25
};

struct NewtonSettings {
  NewtonJacobian jacobian = NewtonJacobian::refreshed;
  double tolerance = 1e-15;  // scaled max-norm of the Newton correction
  int max_iterations = 30;
  /// Chart coordinates beyond this are refused: dexp⁻¹ is singular at 2π,
  /// where its gain (θ/2)/sin(θ/2) is unbounded; at 2π − ½ it is 11.5.
  double chart_limit = 2.0 * std::numbers::pi - 0.5;
};

template <const auto& Tableau, bool Centred>
class ImplicitRkmk {
 public:
  using TableauType = std::remove_cvref_t<decltype(Tableau)>;
  static constexpr auto& tableau = Tableau;
  static constexpr std::size_t stages = TableauType::stages;
  // A symmetric (Gauss) tableau conserves the quadratic invariant |Pi|^2 of
  // the free body's Euler equations (HLW §IV.2).
  static constexpr SchemeFacts facts{
      .order = Tableau.order,
      .properties = {.symmetric = Tableau.symmetric, .conserves_momentum_norm = Tableau.symmetric, .implicit = true},
      .reference = Centred ? "Munthe-Kaas, Appl. Numer. Math. 29 (1999) 115-127; Iserles et al., Acta Numerica 9 "
                             "(2000) 5.3; chart centred at the step midpoint (Zanna, Engo & Munthe-Kaas, BIT 41 "
                             "(2001) 395-421)"
                           : munthe_kaas_reference,
      .tableau = Tableau.citation};
  static constexpr int n = 6 * static_cast<int>(stages);
  using VecN = Eigen::Matrix<double, n, 1>;
  using MatN = Eigen::Matrix<double, n, n>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;

  NewtonSettings newton{};

  ImplicitRkmk() = default;
  explicit ImplicitRkmk(const NewtonSettings& settings) : newton(settings) {}

  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) const {
    VecN Z = VecN::Zero();
    VecN F;
    MatN M;
    Eigen::PartialPivLU<MatN> lu;
    StepStatus status;
    status.converged = false;
    status.residual = std::numeric_limits<double>::infinity();

    // Scales of the convergence test: angles in rad relative to
    // max(1, largest |w_i|), momenta relative to the largest |Π| seen in the step.
    double pi_scale = std::max(s.Pi.norm(), std::numeric_limits<double>::min());
    double angle_scale = 1.0;
    double previous = 0.0;     // |ΔZ_{k−1}|
    double last_theta = 0.0;   // θ_{k−1}
    for (int k = 1; k <= newton.max_iterations; ++k) {
      const bool refresh = k == 1 || newton.jacobian == NewtonJacobian::full ||
                           (newton.jacobian == NewtonJacobian::refreshed && k > 2 && last_theta > 0.25);
      if (!evaluate(model, s, t, h, Z, F, refresh ? &M : nullptr)) {  // outside the chart
        status.reason = "implicit solve did not converge: Newton left the chart of exp (a stage rotation near "
                        "2 pi, where dexp^-1 is singular); reduce --dt";
        return status;
      }
      work.rhs_evaluations += static_cast<std::int64_t>(stages);
      if (refresh) lu.compute(M);
      VecN G = Z;
      for (std::size_t i = 0; i < stages; ++i)
        for (std::size_t j = 0; j < stages; ++j)
          G.template segment<6>(6 * static_cast<int>(i)) -=
              (h * Tableau.a[i][j]) * F.template segment<6>(6 * static_cast<int>(j));
      const VecN dZ = lu.solve(-G);
      Z += dZ;
      status.iterations = k;
      for (std::size_t i = 0; i < stages; ++i) {
        pi_scale = std::max(pi_scale, (s.Pi + Z.template segment<3>(6 * static_cast<int>(i) + 3)).norm());
        angle_scale = std::max(angle_scale, Z.template segment<3>(6 * static_cast<int>(i)).norm());
      }
      const double norm = scaled_norm(dZ, angle_scale, pi_scale);
      status.residual = norm;
      if (!std::isfinite(norm)) return status;
      const double theta = k > 1 ? norm / previous : 1.0;
      last_theta = theta;
      previous = norm;
      // θ_2 = |ΔZ_2|/|ΔZ_1| is no contraction estimate: ΔZ_1 is the whole
      // predictor from Z = 0. Trusting it stopped simplified Newton one
      // iteration early (error 5e-15 per step left, 3e-12 after 1600 steps
      // of gauss4 on free_body_hlw), so the estimate waits for k ≥ 3.
      if (norm <= newton.tolerance || (k > 2 && theta < 1.0 && theta / (1.0 - theta) * norm <= newton.tolerance) ||
          (k > 2 && theta >= 0.5 && norm <= 100.0 * newton.tolerance)) {
        status.converged = true;
        break;
      }
    }
    if (!status.converged) return status;

    Vec3 Theta = Vec3::Zero();
    Vec3 dPi = Vec3::Zero();
    for (std::size_t i = 0; i < stages; ++i) {
      if (Tableau.d[i] == 0.0) continue;
      Theta += Tableau.d[i] * Z.template segment<3>(6 * static_cast<int>(i));
      dPi += Tableau.d[i] * Z.template segment<3>(6 * static_cast<int>(i) + 3);
    }
    s.R = s.R * lie::exp_so3(Theta);
    s.Pi += dPi;
    return status;
  }

 private:
  static double scaled_norm(const VecN& dZ, double angle_scale, double pi_scale) {
    double m = 0.0;
    for (std::size_t i = 0; i < stages; ++i) {
      const int o = 6 * static_cast<int>(i);
      m = std::max(m, dZ.template segment<3>(o).cwiseAbs().maxCoeff() / angle_scale);
      m = std::max(m, dZ.template segment<3>(o + 3).cwiseAbs().maxCoeff() / pi_scale);
    }
    return m;
  }

  /// F(Z) (6s) and, if M is given, the Newton matrix M = I − h (A ⊗ I₆) ∂F/∂Z.
  /// Returns false if a chart coordinate is outside the chart limit.
  template <class Model>
  bool evaluate(const Model& model, const State& s, double t, double h, const VecN& Z, VecN& F, MatN* M) const {
    Vec3 Theta = Vec3::Zero();
    if constexpr (Centred) {
      for (std::size_t i = 0; i < stages; ++i) Theta += Tableau.d[i] * Z.template segment<3>(6 * static_cast<int>(i));
    }
    const Vec3 half = 0.5 * Theta;
    Mat3 R_centre = s.R;
    if constexpr (Centred && Model::has_torque) R_centre = s.R * lie::exp_so3(half);
    std::array<Mat6, stages> D;  // ∂F_i/∂(w_i, δΠ_i) with the chart centre held
    std::array<Mat6, stages> E;  // ∂F_i/∂w_k = D_i·δ_ik + d_k E_i (centred chart only)
    const Mat3& J_inv = model.omega_jacobian();
    for (std::size_t i = 0; i < stages; ++i) {
      const int o = 6 * static_cast<int>(i);
      const Vec3 u = Centred ? Vec3(Z.template segment<3>(o) - half) : Vec3(Z.template segment<3>(o));
      if (!(u.norm() <= newton.chart_limit)) return false;
      const Vec3 Pi_i = s.Pi + Z.template segment<3>(o + 3);
      const Vec3 Omega_i = model.omega(Pi_i);
      const double t_i = t + Tableau.c[i] * h;
      F.template segment<3>(o) = lie::dexpinv_body(u, Omega_i);
      Mat3 exp_u;
      Mat3 R_i = s.R;
      if constexpr (Model::has_torque) {
        exp_u = lie::exp_so3(u);
        R_i = R_centre * exp_u;
      }
      F.template segment<3>(o + 3) = model.momentum_rate(R_i, Pi_i, Omega_i, t_i);
      if (!M) continue;
      const auto jac = model.momentum_rate_jacobian(R_i, Pi_i, Omega_i, t_i);
      Mat6& Di = D[i];
      Di.template block<3, 3>(0, 0) = detail::dexpinv_body_derivative(u, Omega_i);
      Di.template block<3, 3>(0, 3) = lie::dexpinv_body_matrix(u) * J_inv;
      if constexpr (Model::has_torque) {
        Di.template block<3, 3>(3, 0) = jac.attitude * lie::dexp_body(u);
      } else {
        Di.template block<3, 3>(3, 0).setZero();
      }
      Di.template block<3, 3>(3, 3) = jac.momentum;
      if constexpr (Centred) {
        // Moving w_k moves Θ by d_k δw_k, hence u_i by −d_k δw_k/2 and the
        // centre R̄ by β = dexp_body(Θ/2) d_k δw_k/2, which perturbs R_i on
        // the body side by exp(u_i)ᵀ β.
        Mat6& Ei = E[i];
        Ei.setZero();
        Ei.template block<6, 3>(0, 0) = -0.5 * Di.template block<6, 3>(0, 0);
        if constexpr (Model::has_torque) {
          Ei.template block<3, 3>(3, 0) += 0.5 * jac.attitude * exp_u.transpose() * lie::dexp_body(half);
        }
      }
    }
    if (!M) return true;
    M->setIdentity();
    for (std::size_t i = 0; i < stages; ++i) {
      Mat6 sumE = Mat6::Zero();
      if constexpr (Centred) {
        for (std::size_t j = 0; j < stages; ++j) sumE += Tableau.a[i][j] * E[j];
      }
      for (std::size_t k = 0; k < stages; ++k) {
        Mat6 block = Tableau.a[i][k] * D[k];
        if constexpr (Centred) block += Tableau.d[k] * sumE;
        M->template block<6, 6>(6 * static_cast<int>(i), 6 * static_cast<int>(k)) -= h * block;
      }
    }
    return true;
  }
};

using RkmkGauss2 = ImplicitRkmk<tableaus::gauss2, true>;
using RkmkGauss4 = ImplicitRkmk<tableaus::gauss4, true>;
using RkmkRadau5 = ImplicitRkmk<tableaus::radau_iia5, false>;

}  // namespace lgi::integrators
