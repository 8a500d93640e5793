#pragma once
// Embedded Runge–Kutta pairs with a continuous extension (dense output), as
// constexpr data, and their compile-time checks. The pairs themselves are in
// dop853.hpp and verner65.hpp; the scheme that drives them on SO(3) × ℝ³ is
// integrators/schemes/rkmk_pair.hpp.
//
// A pair is an explicit tableau (a, b, c) of order p with
//   - embedded weights b̂ of order p̂ (the error estimate h Σ (b_i − b̂_i) k_i),
//   - optionally a second, lower embedded solution b̌ (DOP853's order-3
//     weights, for the 8(5,3) estimator, HNW I §II.10),
//   - an extended tableau over X ≥ S stages: the S stages of the step, the
//     evaluation at the new point (row b, node 1; FSAL pairs have it among
//     the S stages already), and any extra stages the dense output needs;
//   - dense-output weights b_i(θ) = Σ_{k=1..D} d_k,i θ^k over the X stages,
//     a continuous extension of order q (HNW I §II.6): the step's solution at
//     t_n + θh is y_n + h Σ_i b_i(θ) k_i, and b_i(1) = b_i. A pair may give
//     them instead in the Bernstein basis, b_i(θ) = Σ_{k=0..D} β_k,i B_k(θ),
//     B_k(θ) = C(D,k) θ^k (1 − θ)^(D−k): where the monomial coefficients
//     cancel (Verner's 8(7) interpolant has d_k,i up to 1.4e6 for b_i(θ) of at
//     most 60 on [0, 1], so a rounded d_k,i alone errs by 1.5e-10), the β_k,i
//     stay near the polynomials' size (at most 1.2e3 there), and the sum of
//     nonnegative B_k(θ) adds no cancellation (Farouki & Rajan, Comput. Aided
//     Geom. Design 4 (1987) 191–216).
#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "integrators/tableaus/explicit_tableau.hpp"

namespace lgi::tableaus {

template <std::size_t S, std::size_t X, std::size_t D>
struct DenseEmbeddedTableau : EmbeddedTableau<S> {
  static constexpr std::size_t dense_stages = X;
  static constexpr std::size_t dense_degree = D;
  std::array<double, S> b_low{};  // a second embedded solution; unused when low_order == 0
  int low_order = 0;
  ExplicitTableau<X> extended{};                   // a, c over all X stages; b = b_i(1)
  std::array<std::array<double, X>, D + 1> dense{};  // dense[k][i]: coefficient of θ^k (or B_k) in b_i(θ)
  bool bernstein = false;                           // dense holds Bernstein coefficients β_k,i
  int dense_order = 0;
};

/// A pair over its extended tableau: the step's nodes, rows and weights b are
/// the first S of the extension's (whose row S, for a pair without FSAL, is
/// the new point's); the caller adds b̂ and the dense weights.
template <std::size_t S, std::size_t X, std::size_t D>
constexpr DenseEmbeddedTableau<S, X, D> dense_pair_over(const ExplicitTableau<X>& extended) {
  DenseEmbeddedTableau<S, X, D> t;
  t.extended = extended;
  for (std::size_t i = 0; i < S; ++i) {
    t.c[i] = extended.c[i];
    t.b[i] = extended.b[i];
    for (std::size_t j = 0; j < S; ++j) t.a[i][j] = extended.a[i][j];
  }
  return t;
}

namespace detail {
constexpr double binomial(std::size_t n, std::size_t k) {
  double c = 1.0;
  for (std::size_t j = 1; j <= k; ++j) c = c * static_cast<double>(n + 1 - j) / static_cast<double>(j);
  return c;
}
}  // namespace detail

/// The monomial coefficients d_k,i of b_i(θ): the data, or from Bernstein
/// coefficients d_k = C(D,k) Σ_{j≤k} (−1)^(k−j) C(k,j) β_j (for the checks below).
template <class P>
constexpr std::array<std::array<double, P::dense_stages>, P::dense_degree + 1> monomial_dense(const P& p) {
  if (!p.bernstein) return p.dense;
  constexpr std::size_t D = P::dense_degree;
  std::array<std::array<double, P::dense_stages>, D + 1> d{};
  for (std::size_t k = 0; k <= D; ++k)
    for (std::size_t j = 0; j <= k; ++j) {
      const double w = detail::binomial(D, k) * detail::binomial(k, j) * ((k - j) % 2 == 0 ? 1.0 : -1.0);
      for (std::size_t i = 0; i < P::dense_stages; ++i) d[k][i] += w * p.dense[j][i];
    }
  return d;
}

/// The pairs' order conditions are checked 5× tighter than the default: with
/// heavy cancellation (Verner's b̂ has entries near ±73) the default 1e-14 of
/// the absolute-value scale lets a perturbation of 1e-12 in one weight pass,
/// while both pairs here satisfy every condition to 5e-16 of that scale.
inline constexpr double pair_condition_tolerance = 2e-15;

namespace detail {
/// Whether the extended tableau repeats the step's stages (rows and nodes
/// 0..S-1), its other rows are explicit, and Σ_k d_k = b (so b_i(1) = b_i).
template <class P>
constexpr bool extension_consistent(const P& p) {
  constexpr std::size_t S = P::stages, X = P::dense_stages;
  if (!strictly_lower(p.extended) || !rows_sum_to_nodes(p.extended, 1e-14)) return false;
  for (std::size_t i = 0; i < S; ++i) {
    if (p.extended.c[i] != p.c[i]) return false;
    for (std::size_t j = 0; j < X; ++j)
      if (p.extended.a[i][j] != (j < S ? p.a[i][j] : 0.0)) return false;
  }
  const auto dense = monomial_dense(p);
  for (std::size_t i = 0; i < X; ++i) {
    double at_one = 0.0, scale = 0.0;
    for (const auto& dk : dense) {
      at_one += dk[i];
      scale += abs_value(dk[i]);
    }
    const double b = i < S ? p.b[i] : 0.0;
    if (abs_value(at_one - b) > 1e-14 * (scale > 1.0 ? scale : 1.0)) return false;
    if (p.dense[0][i] != 0.0) return false;  // b_i(0) = 0 (d_0 = β_0)
    // b_i(1) = β_D,i: the same number, as both round the same rational.
    const double ends = p.bernstein ? p.dense[P::dense_degree][i] - b : 0.0;
    if (abs_value(ends) > 4.5e-16 * (abs_value(b) > 1.0 ? abs_value(b) : 1.0)) return false;
  }
  return true;
}
}  // namespace detail

/// The order q of the continuous extension, checked up to one more than the
/// stated order: the smallest order of its coefficients d_1..d_D, the largest
/// q_k ≤ that such that Σ_i d_k,i Φ_i(τ) = δ_{k,|τ|}/γ(τ) for |τ| ≤ q_k
/// (rooted_trees.hpp). The D coefficients share one pass over the trees.
template <const auto& P>
constexpr int dense_output_order() {
  using Pair = std::remove_cvref_t<decltype(P)>;
  constexpr std::size_t D = Pair::dense_degree;
  const auto dense = monomial_dense(P);
  std::array<std::array<double, Pair::dense_stages>, D> coefficients{};
  std::array<int, D> powers{};
  for (std::size_t k = 0; k < D; ++k) {
    coefficients[k] = dense[k + 1];
    powers[k] = static_cast<int>(k + 1);
  }
  const auto orders = orders_of_weights(P.extended.a, coefficients, powers, capped_order(P.dense_order + 1),
                                        pair_condition_tolerance);
  int q = max_checked_order;
  for (const int o : orders) q = o < q ? o : q;
  return q;
}

/// Every compile-time check of a pair: consistency, the stated orders of b,
/// b̂ and b̌ hold and the next ones fail (the three in one pass over the
/// trees), the extension repeats the step and ends at b, and the dense output
/// has exactly its stated order.
template <const auto& P>
constexpr bool pair_checks_out() {
  constexpr double tol = pair_condition_tolerance;
  if (!consistent_explicit(P) || !detail::row_sums_match(P, tol)) return false;
  const auto orders =
      orders_of_weights(P.a, std::array{P.b, P.b_hat, P.b_low}, std::array<int, 3>{}, max_checked_order, tol);
  return orders[0] == capped_order(P.order) && orders[1] == capped_order(P.embedded_order) &&
         (P.low_order == 0 || orders[2] == capped_order(P.low_order)) && detail::extension_consistent(P) &&
         dense_output_order<P>() == capped_order(P.dense_order);
}

}  // namespace lgi::tableaus
