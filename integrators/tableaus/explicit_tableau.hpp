#pragma once
// Explicit Runge–Kutta tableaus as constexpr data, checked at compile time.
// A tableau carries its coefficients, its order and its citation; schemes
// (RKMK, Crouch–Grossman) are generic over it.
#include <array>
#include <cstddef>

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

}  // namespace lgi::tableaus
