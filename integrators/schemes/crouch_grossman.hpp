#pragma once
// Crouch–Grossman methods on SO(3) × ℝ³ (body form).
//
// Crouch & Grossman, J. Nonlinear Sci. 3 (1993) 1–33; Owren & Marthinsen,
// BIT 39 (1999) 116–142, eq. (2.3); docs/math.md §3. For Ṙ = R Ω̂ the stage and update
// products run left to right (the body-form mirror of Y_{n+1} = exp(h b_s F_s)⋯exp(h b_1 F_1) Y_n):
//   R_i = R_n exp(h a_i1 Ω_1) exp(h a_i2 Ω_2) ⋯ exp(h a_i,i−1 Ω_{i−1}),
//   Π_i = Π_n + h Σ_{j<i} a_ij K_j,  Ω_i = J⁻¹Π_i,  K_i = Π_i × Ω_i + τ(R_i, Π_i, Ω_i, t_n + c_i h),
//   R_{n+1} = R_n exp(h b_1 Ω_1) ⋯ exp(h b_s Ω_s),  Π_{n+1} = Π_n + h Σ b_i K_i.
// The stage velocities are used as they are (no dexp⁻¹): the price is extra
// order conditions, which the CG tableaus satisfy. Order: 3 (cg3), 4 (cg4a).
// Conserves RᵀR = I to round-off, no dynamical invariant exactly.
// R exp(ŵ) row by row with the series coefficients of rkmk_pair_kernels.hpp
// (no sin or cos below θ = 1); a stage attitude only in the rows the torque
// reads (row i of R_i needs only row i of the factors before it).
#include <array>

#include "integrators/schemes/rkmk_pair_kernels.hpp"
#include "integrators/core/scheme_interface.hpp"
#include "integrators/tableaus/crouch_grossman.hpp"

namespace lgi::integrators {

template <const auto& Tableau>
class CrouchGrossman {
 public:
  static constexpr auto& tableau = Tableau;
  static constexpr SchemeFacts facts{.order = Tableau.order, .reference = Tableau.citation};
  static constexpr std::size_t stages = std::remove_cvref_t<decltype(Tableau)>::stages;

  template <class Model>
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) const {
    std::array<Vec3, stages> omega;       // Ω_i
    std::array<Vec3, stages> k_momentum;  // K_i
    const unsigned rows = rkmk_pair_detail::torque_rows(model);  // of a stage attitude the torque reads
    for (std::size_t i = 0; i < stages; ++i) {
      Vec3 dPi = Vec3::Zero();
      for (std::size_t j = 0; j < i; ++j) dPi += Tableau.a[i][j] * k_momentum[j];
      const Vec3 Pi_i = s.Pi + h * dPi;
      omega[i] = model.omega(Pi_i);
      if constexpr (Model::has_torque) {
        Mat3 R_i = s.R;
        for (std::size_t j = 0; j < i; ++j) {
          if (Tableau.a[i][j] != 0.0) R_i = rkmk_pair_detail::times_exp(R_i, (h * Tableau.a[i][j]) * omega[j], rows);
        }
        k_momentum[i] = model.momentum_rate(R_i, Pi_i, omega[i], t + Tableau.c[i] * h);
      } else {
        k_momentum[i] = model.momentum_rate(s.R, Pi_i, omega[i], t);
      }
    }
    Vec3 dPi = Vec3::Zero();
    for (std::size_t i = 0; i < stages; ++i) {
      if (Tableau.b[i] != 0.0) s.R = rkmk_pair_detail::times_exp(s.R, (h * Tableau.b[i]) * omega[i]);
      dPi += Tableau.b[i] * k_momentum[i];
    }
    s.Pi += h * dPi;
    work.rhs_evaluations += static_cast<std::int64_t>(stages);
    return {};
  }
};

using Cg3 = CrouchGrossman<tableaus::cg3>;
using Cg4a = CrouchGrossman<tableaus::cg4a>;

}  // namespace lgi::integrators
