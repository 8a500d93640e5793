#pragma once
// Crouch–Grossman tableaus (crouch_grossman.hpp). The classical conditions
// up to the method's order hold, plus the extra non-commutative ones of
// Owren & Marthinsen (BIT 39 (1999) 116–142).
#include "integrators/tableaus/explicit_tableau.hpp"

namespace lgi::tableaus {

/// CG3: Crouch & Grossman, J. Nonlinear Sci. 3 (1993) 1–33; Owren &
/// Marthinsen (1999); HLW, Geometric Numerical Integration, §IV.8.
/// Also DiffMan's 'CG3a'. The extra order-3 condition
/// Σ b_i² c_i + 2 Σ_{i<j} b_i c_i b_j = 1/3 holds exactly.
inline constexpr ExplicitTableau<3> cg3{
    {{{0.0, 0.0, 0.0}, {3.0 / 4.0, 0.0, 0.0}, {119.0 / 216.0, 17.0 / 108.0, 0.0}}},
    {13.0 / 51.0, -2.0 / 3.0, 24.0 / 17.0},
    {0.0, 3.0 / 4.0, 17.0 / 24.0},
    3,
    "Crouch & Grossman, J. Nonlinear Sci. 3 (1993) 1–33; Owren & Marthinsen, BIT 39 (1999)"};

/// CG4a, 5 stages, order 4: Jackiewicz, Marthinsen & Owren, "Construction of
/// Runge–Kutta methods of Crouch–Grossman type of high order", Adv. Comput.
/// Math. 13 (2000) 405–415, Appendix A, Example 1. Values to 16 decimals as
/// in DiffMan 2.02 (setmethod.m, 'CG4a'); a54 = −1.1092979392113465 (some
/// codes print …3565, which breaks the row sum a5· = c5 by 1e-14).
inline constexpr ExplicitTableau<5> cg4a{
    {{{0.0, 0.0, 0.0, 0.0, 0.0},
      {0.8177227988124852, 0.0, 0.0, 0.0, 0.0},
      {0.3199876375476427, 0.0659864263556022, 0.0, 0.0, 0.0},
      {0.9214417194464946, 0.4997857776773573, -1.0969984448371582, 0.0, 0.0},
      {0.3552358559023322, 0.2390958372307326, 1.3918565724203246, -1.1092979392113465, 0.0}}},
    {0.1370831520630755, -0.0183698531564020, 0.7397813985370780, -0.1907142565505889, 0.3322195591068374},
    {0.0, 0.8177227988124852, 0.3859740639032449, 0.3242290522866937, 0.8768903263420429},
    4,
    "Jackiewicz, Marthinsen & Owren, Adv. Comput. Math. 13 (2000) 405–415, App. A, Ex. 1"};

// The 16-decimal literals satisfy the conditions to ~1e-16, not exactly.
static_assert(weights_sum_to_one(cg3) && rows_sum_to_nodes(cg3) && strictly_lower(cg3) &&
              second_order_condition(cg3));
static_assert(weights_sum_to_one(cg4a, 1e-15) && rows_sum_to_nodes(cg4a, 1e-15) && strictly_lower(cg4a) &&
              second_order_condition(cg4a, 1e-15));

/// The extra order-3 condition of Crouch–Grossman methods (Owren &
/// Marthinsen, BIT 39 (1999)): Σ_i b_i² c_i + 2 Σ_{i<j} b_i c_i b_j = 1/3,
/// with the relative tolerance of weights_satisfy_order_conditions.
template <class T>
constexpr bool crouch_grossman_third_order_condition(const T& t, double tolerance = order_condition_tolerance) {
  double sum = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < T::stages; ++i) {
    sum += t.b[i] * t.b[i] * t.c[i];
    scale += abs_value(t.b[i] * t.b[i] * t.c[i]);
    for (std::size_t j = i + 1; j < T::stages; ++j) {
      sum += 2.0 * t.b[i] * t.c[i] * t.b[j];
      scale += abs_value(2.0 * t.b[i] * t.c[i] * t.b[j]);
    }
  }
  return detail::matches(sum, scale, 1.0 / 3.0, tolerance);
}

// The classical conditions are necessary for CG (it is the classical method
// on a commutative group): both hold to their stated order, and CG3 is not
// classically of order 4. The further order-4 CG conditions are not checked.
static_assert(classical_order(cg3) == capped_order(cg3.order));
static_assert(classical_order(cg4a) == capped_order(cg4a.order));
static_assert(crouch_grossman_third_order_condition(cg3) && crouch_grossman_third_order_condition(cg4a));

}  // namespace lgi::tableaus
