#pragma once
// Runge–Kutta–Munthe-Kaas (RKMK) on SO(3) × ℝ³, driven by any explicit tableau.
//
// Munthe-Kaas, "High order Runge–Kutta methods on manifolds", Appl. Numer.
// Math. 29 (1999) 115–127, Algorithm 1; Iserles, Munthe-Kaas, Nørsett &
// Zanna, Acta Numerica 9 (2000) 215–365, §5.3, eq. (5.14); written in body
// form (Ṙ = R Ω̂), see docs/math.md §2:
//   for i = 1..s:  w_i = h Σ_{j<i} a_ij k̃_j,  R_i = R_n exp(w_i),
//                  Π_i = Π_n + h Σ_{j<i} a_ij K_j,  Ω_i = J⁻¹Π_i,
//                  k̃_i = dexp⁻¹_body(w_i) Ω_i = Ω_i + ½ w_i × Ω_i + c(|w_i|) w_i × (w_i × Ω_i),
//                  K_i = Π_i × Ω_i + τ(R_i, Π_i, Ω_i, t_n + c_i h)
//   R_{n+1} = R_n exp(h Σ b_i k̃_i),  Π_{n+1} = Π_n + h Σ b_i K_i.
// With Chart = CayleyChart (rkmk_chart.hpp, `rkmk-cayley4`) exp and dexp⁻¹
// become cay and dcay⁻¹ = Ω + ½ w × Ω + ¼ (w·Ω) w, at the same order.
// Order: that of the tableau (the closed-form dexp⁻¹ is exact, so no
// truncation condition applies). Conserves: RᵀR = I to round-off (the
// attitude only moves by exp); no invariant of the dynamics exactly.
// For a free body the stage attitudes R_i are never formed: the momentum
// field does not depend on R. Otherwise only the rows the torque reads are
// (gravity: Γ = Rᵀe3; rkmk_pair_kernels.hpp's stage_attitude). exp and
// dexp⁻¹ are those of the adaptive pairs (rkmk_pair_kernels.hpp: Taylor
// series below θ = 1, so no sin or cos in a usual step), whose source
// lie/exp_series.hpp the ensemble kernel shares.
#include <array>
#include <type_traits>

#include "integrators/core/flatten_policy.hpp"
#include "integrators/schemes/rkmk_chart.hpp"
#include "integrators/schemes/rkmk_pair_kernels.hpp"
#include "integrators/core/scheme_interface.hpp"
#include "integrators/tableaus/runge_kutta.hpp"

namespace lgi::integrators {

namespace rkmk_detail {
/// The ensemble's RKMK kernel (ensemble/rkmk_kernel.hpp) is compiled for the
/// classical RK4 tableau in exp coordinates (ensemble/kernel_set.hpp): rkmk4.
template <const auto& Tableau, class Chart>
constexpr LaneKernel lane_kernel() {
  using Rk4 = std::remove_cvref_t<decltype(tableaus::classical_rk4)>;
  if constexpr (std::is_same_v<std::remove_cvref_t<decltype(Tableau)>, Rk4> && std::is_same_v<Chart, ExponentialChart>)
    return &Tableau == &tableaus::classical_rk4 ? LaneKernel::rkmk4 : LaneKernel::none;
  else
    return LaneKernel::none;
}
}  // namespace rkmk_detail

template <const auto& Tableau, RkmkChart Chart = ExponentialChart>
class Rkmk {
 public:
  static constexpr auto& tableau = Tableau;
  static constexpr SchemeFacts facts{.order = Tableau.order,
                                     .reference = Chart::reference,
                                     .tableau = Tableau.citation,
                                     .lane_kernel = rkmk_detail::lane_kernel<Tableau, Chart>()};
  static constexpr std::size_t stages = std::remove_cvref_t<decltype(Tableau)>::stages;

  // flatten: the maps, dexp⁻¹, the stage attitude and the torque inlined into
  // one block, as the pairs' run_stages (rkmk_pair.hpp): same bits, ~15% less
  // time per step (docs/performance.md §5).
  template <class Model>
  LGI_FLATTEN StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) const {
    std::array<Vec3, stages> k_algebra;  // k̃_i
    std::array<Vec3, stages> k_momentum; // K_i
    const unsigned rows = rkmk_pair_detail::torque_rows(model);  // of R_i the torque reads
    for (std::size_t i = 0; i < stages; ++i) {
      Vec3 w = Vec3::Zero();
      Vec3 dPi = Vec3::Zero();
      for (std::size_t j = 0; j < i; ++j) {
        const double aij = Tableau.a[i][j];
        if (aij == 0.0) continue;
        w += aij * k_algebra[j];
        dPi += aij * k_momentum[j];
      }
      w *= h;
      const Vec3 Pi_i = s.Pi + h * dPi;
      const Vec3 Omega_i = model.omega(Pi_i);
      rkmk_pair_detail::MapCoefficients m{};
      if (i == 0) {
        k_algebra[i] = Omega_i;
      } else {
        m = Chart::coefficients(lie::exp_series::squared_norm(w.data()));
        Chart::inverse_differential(w.data(), Omega_i, m, k_algebra[i].data());
      }
      if constexpr (Model::has_torque) {
        Mat3 R_i;
        if (i == 0) R_i = s.R;
        else rkmk_pair_detail::stage_attitude(s.R, w.data(), m, rows, R_i);
        k_momentum[i] = model.momentum_rate(R_i, Pi_i, Omega_i, t + Tableau.c[i] * h);
      } else {
        k_momentum[i] = model.momentum_rate(s.R, Pi_i, Omega_i, t);
      }
    }
    Vec3 w = Vec3::Zero();
    Vec3 dPi = Vec3::Zero();
    for (std::size_t i = 0; i < stages; ++i) {
      w += Tableau.b[i] * k_algebra[i];
      dPi += Tableau.b[i] * k_momentum[i];
    }
    const Vec3 hw = h * w;
    s.R = times_map<Chart>(s.R, hw.data());
    s.Pi += h * dPi;
    work.rhs_evaluations += static_cast<std::int64_t>(stages);
    return {};
  }
};

using LieEuler = Rkmk<tableaus::euler>;
using Rkmk2 = Rkmk<tableaus::heun>;
using Rkmk3 = Rkmk<tableaus::kutta3>;
using Rkmk4 = Rkmk<tableaus::classical_rk4>;
/// RK4 in Cayley coordinates R = R_n cay(ŵ) (rkmk_chart.hpp).
using RkmkCayley4 = Rkmk<tableaus::classical_rk4, CayleyChart>;

}  // namespace lgi::integrators
