#pragma once
// Explicit Runge–Kutta tableaus as constexpr data, checked at compile time.
// A tableau carries its coefficients, its order and its citation; schemes
// (RKMK, Crouch–Grossman) are generic over it.
#include <array>
#include <cstddef>
#include <stdexcept>

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

/// Σ b_i = 1 (consistency).
template <class T>
constexpr bool weights_sum_to_one(const T& t, double tolerance = 1e-15) {
  double sum = 0.0;
  for (double bi : t.b) sum += bi;
  return abs_value(sum - 1.0) <= tolerance;
}

/// c_i = Σ_j a_ij (the row-sum condition).
template <class T>
constexpr bool rows_sum_to_nodes(const T& t, double tolerance = 1e-15) {
  for (std::size_t i = 0; i < T::stages; ++i) {
    double sum = 0.0;
    for (std::size_t j = 0; j < T::stages; ++j) sum += t.a[i][j];
    if (abs_value(sum - t.c[i]) > tolerance) return false;
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

// Classical order conditions Σ_i b_i Φ_i(τ) = 1/γ(τ) for the eight rooted
// trees τ with at most four vertices (Butcher, Numerical Methods for ODEs,
// 3rd ed. (2016), Ch. 3; Hairer, Nørsett & Wanner, Solving ODEs I, §II.2).
// RKMK and Crouch–Grossman reduce to the underlying Runge–Kutta method on
// a commutative group, so these conditions are necessary for both; RKMK
// with an order-p tableau has order p, CG needs extra conditions besides.
// Each sum is compared with a relative tolerance: the scale is the same
// sum evaluated with |a_ij|, |b_i|, |c_i|, which bounds its rounding error.

/// Largest order whose conditions are checked (the trees stop at four vertices).
inline constexpr int max_checked_order = 4;

/// Default relative tolerance: the literals are exact rationals or carry
/// 16 digits, so honest tableaus sit near 1e-16 and typos far above 1e-14.
inline constexpr double order_condition_tolerance = 1e-14;

constexpr int capped_order(int order) { return order < max_checked_order ? order : max_checked_order; }

namespace detail {
/// |value − target| ≤ tol · max(scale, |target|).
constexpr bool matches(double value, double scale, double target, double tolerance) {
  const double t = abs_value(target);
  return abs_value(value - target) <= tolerance * (scale > t ? scale : t);
}
}  // namespace detail

/// Row sums c_i = Σ_j a_ij and the order conditions up to `order` (1..4)
/// for the weights w (b, or an embedded b̂) of the tableau t.
template <class T, class W>
constexpr bool weights_satisfy_order_conditions(const T& t, const W& w, int order,
                                                double tolerance = order_condition_tolerance) {
  if (order < 1 || order > max_checked_order)
    throw std::invalid_argument("order conditions are checked for orders 1 to 4 only");
  constexpr std::size_t s = T::stages;
  // (A c)_i, (A c²)_i, (A A c)_i and their counterparts in absolute values.
  std::array<double, s> ac{}, ac_abs{}, ac2{}, ac2_abs{}, aac{}, aac_abs{};
  for (std::size_t i = 0; i < s; ++i) {
    double row = 0.0, row_abs = 0.0;
    for (std::size_t j = 0; j < s; ++j) {
      const double a = t.a[i][j], cj = t.c[j];
      row += a;
      row_abs += abs_value(a);
      ac[i] += a * cj;
      ac_abs[i] += abs_value(a * cj);
      ac2[i] += a * cj * cj;
      ac2_abs[i] += abs_value(a * cj * cj);
    }
    if (!detail::matches(row, row_abs, t.c[i], tolerance)) return false;
  }
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j) {
      aac[i] += t.a[i][j] * ac[j];
      aac_abs[i] += abs_value(t.a[i][j]) * ac_abs[j];
    }
  // Elementary weights Φ_i(τ) with the targets 1/γ(τ), by order.
  struct Condition {
    int order;
    double target;
  };
  constexpr std::array<Condition, 8> conditions{{{1, 1.0},           // Σ b = 1
                                                 {2, 1.0 / 2.0},     // Σ b c = 1/2
                                                 {3, 1.0 / 3.0},     // Σ b c² = 1/3
                                                 {3, 1.0 / 6.0},     // Σ b A c = 1/6
                                                 {4, 1.0 / 4.0},     // Σ b c³ = 1/4
                                                 {4, 1.0 / 8.0},     // Σ b c (A c) = 1/8
                                                 {4, 1.0 / 12.0},    // Σ b A c² = 1/12
                                                 {4, 1.0 / 24.0}}};  // Σ b A A c = 1/24
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    if (conditions[k].order > order) continue;
    double sum = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < s; ++i) {
      const double ci = t.c[i];
      const std::array<double, 8> phi{1.0, ci, ci * ci, ac[i], ci * ci * ci, ci * ac[i], ac2[i], aac[i]};
      const std::array<double, 8> phi_abs{1.0,
                                          abs_value(ci),
                                          ci * ci,
                                          ac_abs[i],
                                          abs_value(ci * ci * ci),
                                          abs_value(ci) * ac_abs[i],
                                          ac2_abs[i],
                                          aac_abs[i]};
      sum += w[i] * phi[k];
      scale += abs_value(w[i]) * phi_abs[k];
    }
    if (!detail::matches(sum, scale, conditions[k].target, tolerance)) return false;
  }
  return true;
}

template <class T>
constexpr bool satisfies_order_conditions(const T& t, int order, double tolerance = order_condition_tolerance) {
  return weights_satisfy_order_conditions(t, t.b, order, tolerance);
}

/// The largest p ≤ 4 whose conditions the weights w satisfy (0 if none).
/// classical_order(t) == capped_order(t.order) asserts both that the stated
/// order holds and, for order < 4, that the next one fails.
template <class T, class W>
constexpr int classical_order_of_weights(const T& t, const W& w, double tolerance = order_condition_tolerance) {
  int p = 0;
  while (p < max_checked_order && weights_satisfy_order_conditions(t, w, p + 1, tolerance)) ++p;
  return p;
}

template <class T>
constexpr int classical_order(const T& t, double tolerance = order_condition_tolerance) {
  return classical_order_of_weights(t, t.b, tolerance);
}

}  // namespace lgi::tableaus
