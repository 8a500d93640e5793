#pragma once
// Implicit schemes for the Cardan top on T³ × ℝ³ (docs/cardan.md §5). The
// Hamiltonian H(q, p) = ½ pᵀM(q)⁻¹p + V(q) is not separable (M depends on q),
// so no explicit symplectic splitting applies; both schemes solve one
// nonlinear system of 6 equations per step.
//
// `cardan-midpoint` (TorusMidpoint), the implicit midpoint rule:
//   x_{n+1} = x_n + h f((x_n + x_{n+1})/2),  x = (q, p),  f = S ∇H
//   (HNW I, §II.7; Hairer–Lubich–Wanner, GNI, §VI.3, Thm. VI.3.5: symplectic).
//   T³ is abelian, so the rule acts on the lifted angles with no chart.
//   Order 2, symplectic, symmetric; conserves every quadratic invariant and
//   the linear invariant p1 (vertical outer axis) to the solver's tolerance.
//   Its energy error is bounded (not zero) over long times.
// `cardan-dg` (TorusDiscreteGradient), Gonzalez's midpoint discrete gradient:
//   x_{n+1} = x_n + h S ∇̄H(x_n, x_{n+1}),
//   ∇̄H(x, x') = ∇H(x̄) + [(H(x') − H(x) − ∇H(x̄)·Δ) / |Δ|²] Δ,  x̄ = (x + x')/2, Δ = x' − x
//   (Gonzalez, J. Nonlinear Sci. 6 (1996) 449, eq. (3.5); McLachlan, Quispel &
//   Robidoux, Phil. Trans. R. Soc. A 357 (1999) 1021, §3). Since ∇̄H·Δ =
//   H(x') − H(x) and Δ = h S ∇̄H with S skew, H(x_{n+1}) = H(x_n) to the
//   solver's tolerance. Order 2, symmetric; not symplectic, and p1 is NOT
//   conserved exactly (the correction term has a q1 component O(h³)).
//
// Newton: G(y) = y − x_n − h Φ(x_n, y) = 0 with the iteration matrix
// I − (h/2) Df(x̄) (exact for the midpoint rule, the leading part for the
// discrete gradient), refreshed every iteration; iterations stop when the
// scaled increment falls below 1e-15 or stops decreasing below 1e-10
// (the round-off floor), at most 50. A step that does not converge reports
// so; the time loop stops the run.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "integrators/core/scheme_interface.hpp"
#include "integrators/system/cardan.hpp"

namespace lgi::integrators::torus {

using system::CardanTop;
using system::Mat6;
using system::TorusState;
using system::Vec6;

namespace detail {

inline Vec6 apply_symplectic(const Vec6& g) {
  Vec6 f;
  f << g.tail<3>(), -g.head<3>();
  return f;
}

/// Solves y = x0 + h Φ(y) by Newton with matrix I − (h/2) Df((x0+y)/2).
template <class Increment>
StepStatus solve_implicit(const CardanTop& model, const Vec6& x0, double h, Vec6& y, WorkCounters& work,
                          Increment&& phi) {
  constexpr int max_iterations = 50;
  StepStatus st;
  double last = std::numeric_limits<double>::infinity();
  for (int it = 1; it <= max_iterations; ++it) {
    const Vec6 mid = 0.5 * (x0 + y);
    const Vec6 residual = y - x0 - h * phi(y);
    const Mat6 A = Mat6::Identity() - (0.5 * h) * model.field_jacobian(system::unstack(mid));
    work.rhs_evaluations += 13;  // Φ and the 12 evaluations of the Jacobian
    const Vec6 delta = A.partialPivLu().solve(-residual);
    y += delta;
    const double scaled = (delta.array().abs() / (1.0 + y.array().abs())).maxCoeff();
    st.iterations = it;
    st.residual = scaled;
    if (!std::isfinite(scaled)) break;
    if (scaled <= 1e-15 || (scaled < 1e-10 && scaled >= 0.5 * last)) {
      st.converged = true;
      return st;
    }
    last = scaled;
  }
  st.converged = false;
  return st;
}

}  // namespace detail

class TorusMidpoint {
 public:
  static constexpr SchemeFacts facts{
      .order = 2,
      .properties = {.symplectic = true, .symmetric = true, .conserves_vertical_momentum = true, .implicit = true},
      .reference = "implicit midpoint rule: Hairer, Lubich & Wanner, Geometric Numerical Integration (2006) VI.3, "
                   "Thm. 3.5; on the abelian group T^3 x R^3"};
  static constexpr bool memoryless_steps = true;

  StepStatus step(const CardanTop& model, TorusState& s, double /*t*/, double h, WorkCounters& work) const {
    const Vec6 x0 = system::stack(s);
    Vec6 y = x0 + h * model.field(s);
    ++work.rhs_evaluations;
    const StepStatus st = detail::solve_implicit(model, x0, h, y, work, [&](const Vec6& yy) {
      return model.field(system::unstack(0.5 * (x0 + yy)));
    });
    s = system::unstack(y);
    return st;
  }
};

class TorusDiscreteGradient {
 public:
  static constexpr SchemeFacts facts{
      .order = 2,
      .properties = {.symmetric = true, .conserves_energy = true, .implicit = true},
      .reference = "Gonzalez, J. Nonlinear Sci. 6 (1996) 449, eq. (3.5); McLachlan, Quispel & Robidoux, "
                   "Phil. Trans. R. Soc. A 357 (1999) 1021"};
  static constexpr bool memoryless_steps = true;

  StepStatus step(const CardanTop& model, TorusState& s, double /*t*/, double h, WorkCounters& work) const {
    const Vec6 x0 = system::stack(s);
    const double H0 = model.energy(s);
    Vec6 y = x0 + h * model.field(s);
    ++work.rhs_evaluations;
    const StepStatus st = detail::solve_implicit(model, x0, h, y, work, [&](const Vec6& yy) {
      return detail::apply_symplectic(discrete_gradient(model, x0, H0, yy));
    });
    s = system::unstack(y);
    return st;
  }

  /// ∇̄H(x0, y) (Gonzalez 1996, eq. (3.5)); the plain midpoint gradient when
  /// |Δ| is at round-off level.
  static Vec6 discrete_gradient(const CardanTop& model, const Vec6& x0, double H0, const Vec6& y) {
    const Vec6 d = y - x0;
    Vec6 grad = model.energy_gradient(system::unstack(0.5 * (x0 + y)));
    const double dd = d.squaredNorm();
    if (dd > 1e-300) grad += ((model.energy(system::unstack(y)) - H0 - grad.dot(d)) / dd) * d;
    return grad;
  }
};

}  // namespace lgi::integrators::torus
