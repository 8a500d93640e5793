#pragma once
// Explicit Runge–Kutta schemes for the Cardan top on T³ × ℝ³
// (integrators/system/cardan.hpp, docs/cardan.md §5).
//
// T³ is an abelian Lie group: its Lie-algebra action on the lifted angles is
// addition, so a Runge–Kutta method on the canonical field x' = f(x),
// x = (q, p) ∈ ℝ⁶, IS the RKMK method on T³ × ℝ³ (all dexp corrections
// vanish; Iserles et al., Acta Numerica 9 (2000), §5.3). No chart, no
// wrapping of the angles.
//
// `cardan-rk4` (TorusRk<classical_rk4>):
//   k_i = f(x_n + h Σ_j a_ij k_j),  x_{n+1} = x_n + h Σ b_i k_i
//   (HNW I, §II.1, eq. (1.8)); order 4, explicit.
// `cardan-dp54` (TorusDp54): Dormand–Prince 5(4) (Dormand & Prince 1980;
//   HNW I, §II.5, Table 5.2) with the controller of HNW I, §II.4, eq. (4.13):
//   err = RMS(e_i / (tol (1 + max(|x_n,i|, |x_{n+1},i|)))),
//   h_new = h min(5, max(0.2, 0.9 err^(−1/5))), no growth right after a rejection.
//   Order 5 (the propagated solution); for references.
// Both conserve the linear invariant p1 (the cyclic momentum of a vertical
// outer axis) to round-off, as every Runge–Kutta method conserves linear
// invariants (Hairer–Lubich–Wanner, Geometric Numerical Integration,
// Thm. IV.1.5): ṗ1 ≡ 0 there, so every stage adds 0 to p1.
#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <vector>

#include "integrators/core/scheme_interface.hpp"
#include "integrators/system/cardan.hpp"
#include "integrators/tableaus/runge_kutta.hpp"

namespace lgi::integrators::torus {

using system::CardanTop;
using system::TorusState;
using system::Vec6;

template <const auto& Tableau>
class TorusRk {
 public:
  static constexpr SchemeFacts facts{
      .order = Tableau.order,
      .properties = {.conserves_vertical_momentum = true},
      .reference = "Runge-Kutta on the abelian group T^3 x R^3 (Iserles et al., Acta Numerica 9 (2000) 5.3)",
      .tableau = Tableau.citation};
  static constexpr bool memoryless_steps = true;

  StepStatus step(const CardanTop& model, TorusState& s, double /*t*/, double h, WorkCounters& work) const {
    constexpr std::size_t S = std::remove_cvref_t<decltype(Tableau)>::stages;
    const Vec6 x0 = system::stack(s);
    std::array<Vec6, S> k;
    for (std::size_t i = 0; i < S; ++i) {
      Vec6 xi = x0;
      for (std::size_t j = 0; j < i; ++j)
        if (Tableau.a[i][j] != 0.0) xi += (h * Tableau.a[i][j]) * k[j];
      k[i] = model.field(system::unstack(xi));
    }
    Vec6 x1 = x0;
    for (std::size_t i = 0; i < S; ++i)
      if (Tableau.b[i] != 0.0) x1 += (h * Tableau.b[i]) * k[i];
    work.rhs_evaluations += static_cast<std::int64_t>(S);
    s = system::unstack(x1);
    return {};
  }
};

using TorusRk4 = TorusRk<tableaus::classical_rk4>;

class TorusDp54 {
 public:
  static constexpr auto& tableau = tableaus::dormand_prince54;
  static constexpr SchemeFacts facts{
      .order = tableau.order,
      .properties = {.conserves_vertical_momentum = true, .adaptive = true},
      .reference = "Runge-Kutta on the abelian group T^3 x R^3; step control HNW I, II.4, eq. (4.13)",
      .tableau = tableau.citation};
  static constexpr std::size_t stages = 7;

  explicit TorusDp54(double tol = 1e-8) : tol_(tol) {}

  double initial_step(const CardanTop& model, const TorusState& s, double /*t*/, double span) const {
    const Vec6 f = model.field(s);
    const double rate = f.norm() / std::max(1.0, system::stack(s).norm());
    if (!(rate > 0.0)) return span;
    return std::min(span, 0.5 * std::pow(tol_, 0.2) / rate);
  }

  /// One step of the 5th-order solution whatever the estimate (order checks).
  StepStatus step(const CardanTop& model, TorusState& s, double t, double h, WorkCounters& work) {
    attempt(model, s, t, h, work, true);
    return {};
  }

  AdaptiveStatus attempt(const CardanTop& model, TorusState& s, double /*t*/, double h, WorkCounters& work,
                         bool force_accept = false) {
    const auto& T = tableau;
    const Vec6 x0 = system::stack(s);
    std::array<Vec6, stages> k;
    for (std::size_t i = 0; i < stages; ++i) {
      Vec6 xi = x0;
      for (std::size_t j = 0; j < i; ++j)
        if (T.a[i][j] != 0.0) xi += (h * T.a[i][j]) * k[j];
      k[i] = model.field(system::unstack(xi));
    }
    work.rhs_evaluations += static_cast<std::int64_t>(stages);
    Vec6 x1 = x0, e = Vec6::Zero();
    for (std::size_t i = 0; i < stages; ++i) {
      x1 += (h * T.b[i]) * k[i];
      e += (h * (T.b[i] - T.b_hat[i])) * k[i];
    }
    double sum = 0.0;
    for (int i = 0; i < 6; ++i) {
      const double sc = tol_ * (1.0 + std::max(std::abs(x0[i]), std::abs(x1[i])));
      sum += (e[i] / sc) * (e[i] / sc);
    }
    const double err = std::sqrt(sum / 6.0);
    AdaptiveStatus a;
    a.error_norm = err;
    a.accepted = force_accept || err <= 1.0;
    double factor = err > 0.0 ? 0.9 * std::pow(err, -0.2) : 5.0;
    factor = std::min(5.0, std::max(0.2, factor));
    if (a.accepted && last_rejected_) factor = std::min(1.0, factor);
    a.h_next = h * factor;
    last_rejected_ = !a.accepted;
    if (a.accepted) s = system::unstack(x1);
    else ++work.rejected_steps;
    return a;
  }

  /// Resume (scheme_interface.hpp): the controller remembers whether the last
  /// attempt was rejected (no growth right after a rejection).
  void save_memory(std::vector<double>& out) const { out.push_back(last_rejected_ ? 1.0 : 0.0); }
  bool restore_memory(std::span<const double> in) {
    if (in.size() != 1 || (in[0] != 0.0 && in[0] != 1.0)) return false;
    last_rejected_ = in[0] == 1.0;
    return true;
  }

 private:
  double tol_;
  bool last_rejected_ = false;
};

}  // namespace lgi::integrators::torus
