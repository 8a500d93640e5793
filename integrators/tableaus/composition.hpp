#pragma once
// Coefficients γ_1..γ_s of symmetric compositions Ψ_h = Φ_{γ_s h} ∘ ⋯ ∘ Φ_{γ_1 h}
// of a symmetric method Φ of order 2 (Hairer, Lubich & Wanner, Geometric
// Numerical Integration, 2nd ed. (2006), §V.3.1–3.2). Checked at compile
// time: symmetry γ_{s+1−i} = γ_i and the order conditions up to order 6
// (plus a necessary one of order 8). Values to 20 digits as in HLW §V.3.2
// and Hairer's gni_comp.f, which agree with Kahan & Li, Math. Comp. 66
// (1997) 1089–1099, Tables 3–4.
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "integrators/tableaus/explicit_tableau.hpp"

namespace lgi::tableaus {

template <std::size_t S>
struct CompositionCoefficients {
  static constexpr std::size_t stages = S;
  std::array<double, S> gamma{};
  int order = 0;
  const char* name = "";
  const char* citation = "";
};

template <std::size_t S>
constexpr bool composition_consistent(const CompositionCoefficients<S>& c, double tolerance = 1e-15) {
  double sum = 0.0;
  for (double g : c.gamma) sum += g;
  if (abs_value(sum - 1.0) > tolerance) return false;
  for (std::size_t i = 0; i < S; ++i)
    if (c.gamma[i] != c.gamma[S - 1 - i]) return false;
  return true;
}

// Order conditions of a symmetric composition of a symmetric order-2 method
// Φ_h = exp(h E1 + h³ E3 + h⁵ E5 + …) (HLW §V.3.2; McLachlan, SIAM J. Sci.
// Comput. 16 (1995) 151–168). By the BCH formula, with Σγ_i = 1:
//   order 4:  Σ γ_i³ = 0                       (E3 term)
//   order 6:  Σ γ_i⁵ = 0                       (E5 term)
//             Σ γ_i³ τ_i² = 0                  ([E1,[E1,E3]] term, given the others)
//   order 8:  Σ γ_i⁷ = 0                       (E7 term; necessary, not sufficient)
// where τ_i = γ_1 + … + γ_{i−1} + γ_i/2 − 1/2 is the midpoint of substep i
// relative to that of the step; even powers of h are absent by symmetry.
// Each sum Σ v_i is compared with tolerance · Σ |v_i|.

/// Default relative tolerance for the 20-digit coefficients rounded to double.
inline constexpr double composition_tolerance = 1e-14;

namespace detail {
constexpr double positive_power(double x, int k) {
  double p = x;
  for (int i = 1; i < k; ++i) p *= x;
  return p;
}
}  // namespace detail

/// Σ γ_i^k = target, relative to Σ |γ_i|^k.
template <std::size_t S>
constexpr bool power_sum_is(const std::array<double, S>& gamma, int k, double target,
                            double tolerance = composition_tolerance) {
  double sum = 0.0, scale = 0.0;
  for (double g : gamma) {
    const double p = detail::positive_power(g, k);
    sum += p;
    scale += abs_value(p);
  }
  return abs_value(sum - target) <= tolerance * (scale > abs_value(target) ? scale : abs_value(target));
}

/// Σ γ_i³ τ_i² = 0, relative to Σ |γ_i³| τ_i².
template <std::size_t S>
constexpr bool bracket_condition_order6(const std::array<double, S>& gamma,
                                        double tolerance = composition_tolerance) {
  double sum = 0.0, scale = 0.0, before = 0.0;
  for (double g : gamma) {
    const double tau = before + 0.5 * g - 0.5;
    sum += g * g * g * tau * tau;
    scale += abs_value(g * g * g) * tau * tau;
    before += g;
  }
  return abs_value(sum) <= tolerance * scale;
}

/// Symmetry and the conditions above up to `order` ≤ 8 (a symmetric method
/// has even order, so order 3 asks for the conditions of order 4, etc.).
template <std::size_t S>
constexpr bool composition_satisfies_order_conditions(const CompositionCoefficients<S>& c, int order,
                                                      double tolerance = composition_tolerance) {
  if (order < 1 || order > 8)
    throw std::invalid_argument("composition order conditions are checked up to order 8 only");
  for (std::size_t i = 0; i < S; ++i)
    if (c.gamma[i] != c.gamma[S - 1 - i]) return false;
  if (!power_sum_is(c.gamma, 1, 1.0, tolerance)) return false;
  if (order >= 3 && !power_sum_is(c.gamma, 3, 0.0, tolerance)) return false;
  if (order >= 5 && !(power_sum_is(c.gamma, 5, 0.0, tolerance) && bracket_condition_order6(c.gamma, tolerance)))
    return false;
  if (order >= 7 && !power_sum_is(c.gamma, 7, 0.0, tolerance)) return false;
  return true;
}

/// Builds the symmetric array from its first half (and the middle one,
/// fixed by Σγ = 1).
template <std::size_t S, std::size_t H>
constexpr std::array<double, S> symmetric_from_half(const std::array<double, H>& half) {
  static_assert(S == 2 * H + 1);
  std::array<double, S> g{};
  double sum = 0.0;
  for (std::size_t i = 0; i < H; ++i) {
    g[i] = g[S - 1 - i] = half[i];
    sum += 2.0 * half[i];
  }
  g[H] = 1.0 - sum;
  return g;
}

namespace detail {
// 2^(1/3) and 4^(1/3) to 20 digits (std::cbrt is not constexpr in C++20).
inline constexpr double cbrt2 = 1.2599210498948731648;
inline constexpr double cbrt4 = 1.5874010519681994748;
}  // namespace detail

/// Triple jump, order 4: γ1 = γ3 = 1/(2 − 2^(1/3)), γ2 = 1 − 2γ1
/// (Yoshida, Phys. Lett. A 150 (1990) 262–268; HLW eq. (V.3.5)).
inline constexpr CompositionCoefficients<3> yoshida4{
    symmetric_from_half<3>(std::array<double, 1>{1.0 / (2.0 - detail::cbrt2)}), 4, "yoshida4",
    "Yoshida, Phys. Lett. A 150 (1990); HLW V.3 eq. (3.5)"};

/// Suzuki's fractal, order 4, 5 stages: γ1 = γ2 = γ4 = γ5 = 1/(4 − 4^(1/3))
/// (Suzuki, Phys. Lett. A 146 (1990) 319–323; HLW eq. (V.3.6)).
inline constexpr CompositionCoefficients<5> suzuki4{
    symmetric_from_half<5>(std::array<double, 2>{1.0 / (4.0 - detail::cbrt4), 1.0 / (4.0 - detail::cbrt4)}), 4,
    "suzuki4", "Suzuki, Phys. Lett. A 146 (1990); HLW V.3 eq. (3.6)"};

/// Kahan & Li, order 6, 9 stages (HLW §V.3.2, p. 158; gni_comp.f).
inline constexpr CompositionCoefficients<9> kahan_li6{
    symmetric_from_half<9>(std::array<double, 4>{0.39216144400731413928, 0.33259913678935943860,
                                                 -0.70624617255763935981, 0.08221359629355080023}),
    6, "kahan-li6", "Kahan & Li, Math. Comp. 66 (1997); HLW V.3.2 (middle 0.79854399093482996340)"};

/// Kahan & Li, order 8, 17 stages (HLW §V.3.2, p. 158; gni_comp.f).
inline constexpr CompositionCoefficients<17> kahan_li8{
    symmetric_from_half<17>(std::array<double, 8>{0.13020248308889008088, 0.56116298177510838456,
                                                  -0.38947496264484728641, 0.15884190655515560090,
                                                  -0.39590389413323757734, 0.18453964097831570709,
                                                  0.25837438768632204729, 0.29501172360931029887}),
    8, "kahan-li8", "Kahan & Li, Math. Comp. 66 (1997); HLW V.3.2 (middle -0.60550853383003451170)"};

static_assert(composition_consistent(yoshida4));
static_assert(composition_consistent(suzuki4));
static_assert(composition_consistent(kahan_li6));
static_assert(composition_consistent(kahan_li8));
// The middle coefficients implied by Σγ = 1 match the published ones.
static_assert(abs_value(kahan_li6.gamma[4] - 0.79854399093482996340) < 1e-15);
static_assert(abs_value(kahan_li8.gamma[8] + 0.60550853383003451170) < 1e-15);

// Each composition has its stated order (order 8: the necessary conditions only).
static_assert(composition_satisfies_order_conditions(yoshida4, yoshida4.order));
static_assert(composition_satisfies_order_conditions(suzuki4, suzuki4.order));
static_assert(composition_satisfies_order_conditions(kahan_li6, kahan_li6.order));
static_assert(composition_satisfies_order_conditions(kahan_li8, kahan_li8.order));
// The checks can fail: the order-4 methods have Σγ⁵ ≠ 0 (and violate the
// bracket condition), and Kahan–Li 6 has Σγ⁷ ≠ 0.
static_assert(!power_sum_is(yoshida4.gamma, 5, 0.0) && !power_sum_is(suzuki4.gamma, 5, 0.0));
static_assert(!bracket_condition_order6(yoshida4.gamma) && !bracket_condition_order6(suzuki4.gamma));
static_assert(!composition_satisfies_order_conditions(yoshida4, 6) &&
              !composition_satisfies_order_conditions(suzuki4, 6) &&
              !composition_satisfies_order_conditions(kahan_li6, 8));

}  // namespace lgi::tableaus
