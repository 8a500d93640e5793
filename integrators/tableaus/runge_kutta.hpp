#pragma once
// Classical explicit Runge–Kutta tableaus used by RKMK (rkmk.hpp).
// Sources: Hairer, Nørsett & Wanner, Solving ODEs I (2nd ed., 1993), §II.1
// Table 1.1–1.2 and §II.5 Table 5.2; Dormand & Prince, J. Comput. Appl.
// Math. 6 (1980) 19–26 ("RK5(4)7M"), checked against Boost.Odeint's
// runge_kutta_dopri5.hpp.
#include "integrators/tableaus/explicit_tableau.hpp"

namespace lgi::tableaus {

/// Explicit Euler (HNW I, §II.1).
inline constexpr ExplicitTableau<1> euler{{{{0.0}}}, {1.0}, {0.0}, 1, "Euler (HNW I, §II.1)"};

/// Heun's method, order 2 (HNW I, Table 1.1, "Heun").
inline constexpr ExplicitTableau<2> heun{
    {{{0.0, 0.0}, {1.0, 0.0}}}, {0.5, 0.5}, {0.0, 1.0}, 2, "Heun's method (HNW I, §II.1, Table 1.1)"};

/// Kutta's third-order method (HNW I, Table 1.1, "Kutta 3").
inline constexpr ExplicitTableau<3> kutta3{
    {{{0.0, 0.0, 0.0}, {0.5, 0.0, 0.0}, {-1.0, 2.0, 0.0}}},
    {1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0},
    {0.0, 0.5, 1.0},
    3,
    "Kutta's third-order method (HNW I, §II.1, Table 1.1)"};

/// The classical fourth-order method (HNW I, Table 1.2, left).
inline constexpr ExplicitTableau<4> classical_rk4{
    {{{0.0, 0.0, 0.0, 0.0}, {0.5, 0.0, 0.0, 0.0}, {0.0, 0.5, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}}},
    {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0},
    {0.0, 0.5, 0.5, 1.0},
    4,
    "classical Runge–Kutta (HNW I, §II.1, Table 1.2)"};

/// Dormand–Prince 5(4), FSAL (Dormand & Prince 1980; HNW I, Table 5.2).
inline constexpr EmbeddedTableau<7> dormand_prince54 = [] {
  EmbeddedTableau<7> t;
  t.a = {{{0, 0, 0, 0, 0, 0, 0},
          {1.0 / 5, 0, 0, 0, 0, 0, 0},
          {3.0 / 40, 9.0 / 40, 0, 0, 0, 0, 0},
          {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0, 0, 0},
          {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0, 0, 0},
          {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656, 0, 0},
          {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0}}};
  t.b = {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0};
  t.c = {0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0};
  t.order = 5;
  t.citation = "Dormand & Prince, J. Comput. Appl. Math. 6 (1980) 19–26; HNW I, §II.5, Table 5.2";
  t.b_hat = {5179.0 / 57600, 0, 7571.0 / 16695, 393.0 / 640, -92097.0 / 339200, 187.0 / 2100, 1.0 / 40};
  t.embedded_order = 4;
  t.first_same_as_last = true;
  return t;
}();

static_assert(consistent_explicit(euler));
static_assert(consistent_explicit(heun));
static_assert(consistent_explicit(kutta3));
static_assert(consistent_explicit(classical_rk4));
static_assert(consistent_explicit(dormand_prince54));

// Classical order conditions (Butcher trees up to four vertices), against
// the stated order: holds up to min(order, 4) and, below 4, fails at
// order + 1 (Euler is not order 2, Heun not 3, Kutta not 4).
static_assert(classical_order(euler) == capped_order(euler.order));
static_assert(classical_order(heun) == capped_order(heun.order));
static_assert(classical_order(kutta3) == capped_order(kutta3.order));
static_assert(classical_order(classical_rk4) == capped_order(classical_rk4.order));
static_assert(classical_order(dormand_prince54) == capped_order(dormand_prince54.order));
static_assert(classical_order_of_weights(dormand_prince54, dormand_prince54.b_hat) ==
              capped_order(dormand_prince54.embedded_order));
static_assert(satisfies_order_conditions(heun, heun.order) && !satisfies_order_conditions(heun, heun.order + 1));
static_assert([] {
  double s = 0.0;
  for (double x : dormand_prince54.b_hat) s += x;
  return abs_value(s - 1.0) <= 1e-15;
}(), "Dormand–Prince embedded weights must sum to 1");

}  // namespace lgi::tableaus
