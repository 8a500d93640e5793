#pragma once
// Implicit Runge–Kutta tableaus (fully implicit collocation methods) as
// constexpr data, checked at compile time, for the implicit RKMK engine
// (../implicit_rkmk.hpp).
//
// Sources:
//  - Gauss–Legendre collocation: Hairer & Wanner, Solving ODEs II (2nd ed.,
//    1996), §IV.5, Table 5.1 (s = 1, the implicit midpoint rule) and
//    Table 5.2 (s = 2, order 4; Hammer & Hollingsworth 1955, Butcher 1964);
//    also Hairer, Lubich & Wanner, GNI (2006), §II.1.3, Table 1.1.
//  - Radau IIA, s = 3, order 5: Hairer & Wanner, Solving ODEs II, §IV.5,
//    Table 5.6 (Ehle 1969; the method of the RADAU5 code).
// Every coefficient was re-derived symbolically (sympy) from the collocation
// conditions C(s) and the quadrature conditions before it was typed here.
//
// Besides (a, b, c) each tableau carries d = bᵀA⁻¹, so that the update can
// be taken from the converged stage increments Z_i = h Σ_j a_ij k_j as
// y_{n+1} = y_n + Σ_i d_i Z_i without a further evaluation of the field
// (HW II, §IV.8, eq. (8.2b)); for the stiffly accurate Radau IIA d = e_s.
#include <array>
#include <cstddef>

#include "integrators/tableaus/explicit_tableau.hpp"

namespace lgi::tableaus {

template <std::size_t S>
struct ImplicitTableau {
  static constexpr std::size_t stages = S;
  std::array<std::array<double, S>, S> a{};
  std::array<double, S> b{};
  std::array<double, S> c{};
  std::array<double, S> d{};  // bᵀ A⁻¹
  int order = 0;
  int stage_order = 0;        // q of the simplifying assumption C(q)
  bool symmetric = false;     // a_{s+1−i, s+1−j} + a_ij = b_j (HLW §V.2, Theorem 2.3)
  bool stiffly_accurate = false;  // a_sj = b_j (HW II, §IV.3)
  const char* citation = "";
};

namespace detail {
// √3 and √6 to 20 digits (the nearest doubles are what matter).
inline constexpr double sqrt3 = 1.7320508075688772935;
inline constexpr double sqrt6 = 2.4494897427831780982;

constexpr double power(double x, int k) {
  double p = 1.0;
  for (int i = 0; i < k; ++i) p *= x;
  return p;
}
}  // namespace detail

/// B(p): Σ_i b_i c_i^(k−1) = 1/k for k = 1..p (the quadrature has order p).
template <class T>
constexpr bool quadrature_order(const T& t, int p, double tolerance = 1e-15) {
  for (int k = 1; k <= p; ++k) {
    double sum = 0.0;
    for (std::size_t i = 0; i < T::stages; ++i) sum += t.b[i] * detail::power(t.c[i], k - 1);
    if (abs_value(sum - 1.0 / k) > tolerance) return false;
  }
  return true;
}

/// C(q): Σ_j a_ij c_j^(k−1) = c_i^k / k for k = 1..q, every row (collocation).
template <class T>
constexpr bool stage_order_conditions(const T& t, int q, double tolerance = 1e-15) {
  for (int k = 1; k <= q; ++k)
    for (std::size_t i = 0; i < T::stages; ++i) {
      double sum = 0.0;
      for (std::size_t j = 0; j < T::stages; ++j) sum += t.a[i][j] * detail::power(t.c[j], k - 1);
      if (abs_value(sum - detail::power(t.c[i], k) / k) > tolerance) return false;
    }
  return true;
}

/// dᵀA = b, i.e. d = bᵀA⁻¹.
template <class T>
constexpr bool update_weights_consistent(const T& t, double tolerance = 1e-14) {
  for (std::size_t j = 0; j < T::stages; ++j) {
    double sum = 0.0;
    for (std::size_t i = 0; i < T::stages; ++i) sum += t.d[i] * t.a[i][j];
    if (abs_value(sum - t.b[j]) > tolerance) return false;
  }
  return true;
}

/// The symmetry condition of a Runge–Kutta method (HLW §V.2, eq. (2.4)):
/// a_{s+1−i, s+1−j} + a_ij = b_j and b_{s+1−i} = b_i.
template <class T>
constexpr bool symmetric_coefficients(const T& t, double tolerance = 1e-15) {
  constexpr std::size_t s = T::stages;
  for (std::size_t i = 0; i < s; ++i) {
    if (abs_value(t.b[s - 1 - i] - t.b[i]) > tolerance) return false;
    for (std::size_t j = 0; j < s; ++j)
      if (abs_value(t.a[s - 1 - i][s - 1 - j] + t.a[i][j] - t.b[j]) > tolerance) return false;
  }
  return true;
}

/// a_sj = b_j and c_s = 1.
template <class T>
constexpr bool stiffly_accurate_coefficients(const T& t) {
  constexpr std::size_t s = T::stages;
  for (std::size_t j = 0; j < s; ++j)
    if (t.a[s - 1][j] != t.b[j]) return false;
  return t.c[s - 1] == 1.0;
}

template <class T>
constexpr bool consistent_implicit(const T& t) {
  return weights_sum_to_one(t) && rows_sum_to_nodes(t) && update_weights_consistent(t) &&
         quadrature_order(t, t.order) &&  // collocation: the order is the quadrature order (HW II, Th. IV.5.2)
         stage_order_conditions(t, t.stage_order) && (!t.symmetric || symmetric_coefficients(t)) &&
         (!t.stiffly_accurate || stiffly_accurate_coefficients(t));
}

/// Gauss–Legendre, s = 1: the implicit midpoint rule (HW II, Table 5.1).
inline constexpr ImplicitTableau<1> gauss2{
    {{{0.5}}}, {1.0}, {0.5}, {2.0}, 2, 1, true, false,
    "Gauss-Legendre s = 1, implicit midpoint (Hairer & Wanner, Solving ODEs II, IV.5, Table 5.1)"};

/// Gauss–Legendre, s = 2, order 4 (HW II, Table 5.2; Hammer & Hollingsworth 1955):
/// c = ½ ∓ √3/6, a = [[¼, ¼ − √3/6], [¼ + √3/6, ¼]], b = (½, ½); d = (−√3, √3).
inline constexpr ImplicitTableau<2> gauss4{
    {{{0.25, 0.25 - detail::sqrt3 / 6.0}, {0.25 + detail::sqrt3 / 6.0, 0.25}}},
    {0.5, 0.5},
    {0.5 - detail::sqrt3 / 6.0, 0.5 + detail::sqrt3 / 6.0},
    {-detail::sqrt3, detail::sqrt3},
    4,
    2,
    true,
    false,
    "Gauss-Legendre s = 2, order 4 (Hairer & Wanner, Solving ODEs II, IV.5, Table 5.2)"};

/// Radau IIA, s = 3, order 5, stage order 3, L-stable, stiffly accurate
/// (HW II, §IV.5, Table 5.6): c = ((4 − √6)/10, (4 + √6)/10, 1),
///   a = [[(88 − 7√6)/360,     (296 − 169√6)/1800, (−2 + 3√6)/225],
///        [(296 + 169√6)/1800, (88 + 7√6)/360,     (−2 − 3√6)/225],
///        [(16 − √6)/36,       (16 + √6)/36,       1/9]],  b = last row.
inline constexpr ImplicitTableau<3> radau_iia5{
    {{{(88.0 - 7.0 * detail::sqrt6) / 360.0, (296.0 - 169.0 * detail::sqrt6) / 1800.0,
       (-2.0 + 3.0 * detail::sqrt6) / 225.0},
      {(296.0 + 169.0 * detail::sqrt6) / 1800.0, (88.0 + 7.0 * detail::sqrt6) / 360.0,
       (-2.0 - 3.0 * detail::sqrt6) / 225.0},
      {(16.0 - detail::sqrt6) / 36.0, (16.0 + detail::sqrt6) / 36.0, 1.0 / 9.0}}},
    {(16.0 - detail::sqrt6) / 36.0, (16.0 + detail::sqrt6) / 36.0, 1.0 / 9.0},
    {(4.0 - detail::sqrt6) / 10.0, (4.0 + detail::sqrt6) / 10.0, 1.0},
    {0.0, 0.0, 1.0},
    5,
    3,
    false,
    true,
    "Radau IIA s = 3, order 5 (Hairer & Wanner, Solving ODEs II, IV.5, Table 5.6)"};

static_assert(consistent_implicit(gauss2));
static_assert(consistent_implicit(gauss4));
static_assert(consistent_implicit(radau_iia5));
static_assert(quadrature_order(gauss4, 4) && !quadrature_order(gauss4, 5, 1e-6), "Gauss s = 2 has quadrature order exactly 4");
static_assert(quadrature_order(radau_iia5, 5) && !quadrature_order(radau_iia5, 6, 1e-6),
              "Radau s = 3 has quadrature order exactly 5");

}  // namespace lgi::tableaus
