#pragma once
// Explicit Runge–Kutta tableaus as constexpr data, checked at compile time.
// A tableau carries its coefficients, its order and its citation; schemes
// (RKMK, Crouch–Grossman) are generic over it.
#include <array>
#include <cstddef>
#include <stdexcept>

#include "integrators/tableaus/rooted_trees.hpp"

namespace lgi::tableaus {

template <std::size_t S>
struct ExplicitTableau {
  static constexpr std::size_t stages = S;
  std::array<std::array<double, S>, S> a{};  // strictly lower triangular
  std::array<double, S> b{};
  std::array<double, S> c{};
  int order = 0;
  const char* citation = "";
};

/// An explicit tableau with an embedded lower-order solution b̂ for error control.
template <std::size_t S>
struct EmbeddedTableau : ExplicitTableau<S> {
  std::array<double, S> b_hat{};
  int embedded_order = 0;
  bool first_same_as_last = false;  // row s of a equals b, so stage s is stage 1 of the next step
};

constexpr double abs_value(double x) { return x < 0 ? -x : x; }

// The consistency sums below are compared with tolerance · max(1, Σ|terms|):
// absolute for tableaus with coefficients of order one, relative to the
// terms where they are large (DOP853's rows hold entries near 40).

/// Σ b_i = 1 (consistency).
template <class T>
constexpr bool weights_sum_to_one(const T& t, double tolerance = 1e-15) {
  double sum = 0.0, size = 1.0;
  for (double bi : t.b) {
    sum += bi;
    size += abs_value(bi);
  }
  return abs_value(sum - 1.0) <= tolerance * (size - 1.0 > 1.0 ? size - 1.0 : 1.0);
}

/// c_i = Σ_j a_ij (the row-sum condition).
template <class T>
constexpr bool rows_sum_to_nodes(const T& t, double tolerance = 1e-15) {
  for (std::size_t i = 0; i < T::stages; ++i) {
    double sum = 0.0, size = 0.0;
    for (std::size_t j = 0; j < T::stages; ++j) {
      sum += t.a[i][j];
      size += abs_value(t.a[i][j]);
    }
    if (abs_value(sum - t.c[i]) > tolerance * (size > 1.0 ? size : 1.0)) return false;
  }
  return true;
}

/// a_ij = 0 for j ≥ i.
template <class T>
constexpr bool strictly_lower(const T& t) {
  for (std::size_t i = 0; i < T::stages; ++i)
    for (std::size_t j = i; j < T::stages; ++j)
      if (t.a[i][j] != 0.0) return false;
  return true;
}

/// Σ b_i c_i = 1/2: the order-2 condition, a cheap guard against a mistyped
/// weight or node.
template <class T>
constexpr bool second_order_condition(const T& t, double tolerance = 1e-15) {
  double sum = 0.0;
  for (std::size_t i = 0; i < T::stages; ++i) sum += t.b[i] * t.c[i];
  return abs_value(sum - 0.5) <= tolerance;
}

template <class T>
constexpr bool consistent_explicit(const T& t) {
  return weights_sum_to_one(t) && rows_sum_to_nodes(t) && strictly_lower(t) &&
         (t.order < 2 || second_order_condition(t));
}

// Classical order conditions Σ_i b_i Φ_i(τ) = 1/γ(τ) for every rooted tree
// τ with at most max_checked_order vertices (rooted_trees.hpp: 486 trees;
// Butcher, Numerical Methods for ODEs, 3rd ed. (2016), Ch. 3; Hairer,
// Nørsett & Wanner, Solving ODEs I, §II.2).
// RKMK and Crouch–Grossman reduce to the underlying Runge–Kutta method on
// a commutative group, so these conditions are necessary for both; RKMK
// with an order-p tableau has order p, CG needs extra conditions besides.
// Each sum is compared with a relative tolerance: the scale is the same sum
// evaluated with |a_ij|, |b_i|, which bounds its rounding error.

/// Largest order whose conditions are checked (the trees stop at nine
/// vertices, so an order-8 tableau is also checked to fail order 9).
inline constexpr int max_checked_order = max_tree_order;

/// Default relative tolerance: the literals are exact rationals or carry
/// 16 digits or more, so honest tableaus sit near 1e-16 and typos far above 1e-14.
inline constexpr double order_condition_tolerance = 1e-14;

constexpr int capped_order(int order) { return order < max_checked_order ? order : max_checked_order; }

namespace detail {
/// |value − target| ≤ tol · max(scale, |target|).
constexpr bool matches(double value, double scale, double target, double tolerance) {
  const double t = abs_value(target);
  return abs_value(value - target) <= tolerance * (scale > t ? scale : t);
}
/// c_i = Σ_j a_ij, to the relative tolerance.
template <class T>
constexpr bool row_sums_match(const T& t, double tolerance) {
  for (std::size_t i = 0; i < T::stages; ++i) {
    double row = 0.0, row_abs = 0.0;
    for (std::size_t j = 0; j < T::stages; ++j) {
      row += t.a[i][j];
      row_abs += abs_value(t.a[i][j]);
    }
    if (!matches(row, row_abs, t.c[i], tolerance)) return false;
  }
  return true;
}
}  // namespace detail

/// Row sums c_i = Σ_j a_ij and the order conditions up to `order`
/// (1..max_checked_order) for the weights w (b, or an embedded b̂) of the tableau t.
template <class T, class W>
constexpr bool weights_satisfy_order_conditions(const T& t, const W& w, int order,
                                                double tolerance = order_condition_tolerance) {
  if (order < 1 || order > max_checked_order)
    throw std::invalid_argument("order conditions are checked for orders 1 to 9 only");
  return detail::row_sums_match(t, tolerance) && order_of_weights(t.a, w, order, tolerance) >= order;
}

template <class T>
constexpr bool satisfies_order_conditions(const T& t, int order, double tolerance = order_condition_tolerance) {
  return weights_satisfy_order_conditions(t, t.b, order, tolerance);
}

/// The largest p ≤ max_checked_order whose conditions the weights w satisfy
/// (0 if none, or if the row sums are not the nodes).
/// classical_order(t) == capped_order(t.order) asserts both that the stated
/// order holds and, below max_checked_order, that the next one fails.
template <class T, class W>
constexpr int classical_order_of_weights(const T& t, const W& w, double tolerance = order_condition_tolerance) {
  if (!detail::row_sums_match(t, tolerance)) return 0;
  return order_of_weights(t.a, w, max_checked_order, tolerance);
}

template <class T>
constexpr int classical_order(const T& t, double tolerance = order_condition_tolerance) {
  return classical_order_of_weights(t, t.b, tolerance);
}

}  // namespace lgi::tableaus
