#pragma once
// RKMK3-Heun: Runge–Kutta–Munthe-Kaas on SO(3) × ℝ³ (lgi's Rkmk, its header
// states the update formulas: Munthe-Kaas, Appl. Numer. Math. 29 (1999),
// Algorithm 1) driven by Heun's third-order tableau, which lgi does not ship
// (its rkmk3 uses Kutta's):
//     0   |
//    1/3  | 1/3
//    2/3  |  0   2/3
//   ------+----------------
//         | 1/4   0   3/4
// (Heun, Z. Math. Phys. 45 (1900) 23–38; Hairer, Nørsett & Wanner, Solving
// ODEs I, §II.1, Table 1.1). Order 3, 3 evaluations a step; conserves
// RᵀR = I to round-off and no invariant of the dynamics exactly.
#include "integrators/schemes/rkmk.hpp"
#include "integrators/tableaus/explicit_tableau.hpp"

namespace custom {

inline constexpr lgi::tableaus::ExplicitTableau<3> heun3{
    {{{0.0, 0.0, 0.0}, {1.0 / 3.0, 0.0, 0.0}, {0.0, 2.0 / 3.0, 0.0}}},
    {0.25, 0.0, 0.75},
    {0.0, 1.0 / 3.0, 2.0 / 3.0},
    3,
    "Heun's third-order method (Heun 1900; HNW I, Table 1.1)"};

// Checked at compile time, as lgi's own tableaus: consistency, and the order
// conditions hold up to the stated order and fail above it.
static_assert(lgi::tableaus::consistent_explicit(heun3));
static_assert(lgi::tableaus::satisfies_order_conditions(heun3, heun3.order) &&
              !lgi::tableaus::satisfies_order_conditions(heun3, heun3.order + 1));

/// The scheme type: order, citation and step come with lgi's Rkmk.
using Rkmk3Heun = lgi::integrators::Rkmk<heun3>;

}  // namespace custom
