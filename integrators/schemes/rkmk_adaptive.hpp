#pragma once
// The adaptive RKMK schemes: rkmk_pair.hpp (stages, error estimate on the
// algebra and in Π, PI controller, dense output, resume memory) on five pairs.
//
//   rkmk-dp54      Dormand–Prince 5(4), FSAL, 6 evaluations per step (Dormand &
//                  Prince 1980; HNW I Table 5.2); I controller (β = 0) with
//                  err^(−1/5), factors in [0.2, 5], as HNW I eq. (4.13). No
//                  dense output: output times are landed on.
//   rkmk-verner65  Verner's most efficient 6(5) pair IIIXb, FSAL, 8 evaluations
//                  per step, interpolant of order 6 (tableaus/verner65.hpp).
//   rkmk-dop853    DOP853, 12 evaluations per step, 8(5,3) error estimator,
//                  dense output of order 7 (tableaus/dop853.hpp).
//   rkmk-verner87  Verner's most efficient 8(7) pair IIa, 13 evaluations per
//                  step, interpolant of order 8 (8 more evaluations in a step
//                  with an output time or an event crossing inside, which
//                  the interpolant locates; tableaus/verner87.hpp).
//   rkmk-verner98  Verner's most efficient 9(8) pair IIa, 16 evaluations per
//                  step, interpolant of order 9 (10 more; tableaus/verner98.hpp).
// The two Verner pairs use DOP853's controller constants with their own
// exponent 1/(p̂ + 1); at equal error they need 7–25% fewer evaluations than
// DOP853 on the heavy tops (docs/performance.md §6).
// The controllers' β and bounds were chosen on work-precision runs of the
// heavy tops (docs/performance.md §2, §6); each is a PI controller in the range
// HNW I §II.4 recommends (β ≤ 0.4/q).
#include <tuple>

#include "integrators/schemes/rkmk_pair.hpp"
#include "integrators/tableaus/dop853.hpp"
#include "integrators/tableaus/runge_kutta.hpp"
#include "integrators/tableaus/verner65.hpp"
#include "integrators/tableaus/verner87.hpp"
#include "integrators/tableaus/verner98.hpp"

namespace lgi::integrators {

inline constexpr PairControl dp54_control{.exponent = 1.0 / 5.0, .beta = 0.0, .safety = 0.9, .fac_min = 0.2,
                                          .fac_max = 5.0};
inline constexpr PairControl verner65_control{.exponent = 1.0 / 6.0, .beta = 0.04, .safety = 0.9,
                                              .fac_min = 0.2, .fac_max = 5.0};
inline constexpr PairControl dop853_control{.exponent = 1.0 / 8.0, .beta = 0.04, .safety = 0.9,
                                            .fac_min = 1.0 / 3.0, .fac_max = 6.0};
/// DOP853's constants with the 9(8) pair's exponent 1/(p̂ + 1) (the 8(7) pair's is DOP853's own).
inline constexpr PairControl verner98_control = [] {
  PairControl c = dop853_control;
  c.exponent = 1.0 / 9.0;
  return c;
}();

using RkmkDp54 = RkmkPair<tableaus::dormand_prince54, dp54_control>;
using RkmkVerner65 = RkmkPair<tableaus::verner65, verner65_control>;
using RkmkDop853 = RkmkPair<tableaus::dop853, dop853_control>;
using RkmkVerner87 = RkmkPair<tableaus::verner87, dop853_control>;
using RkmkVerner98 = RkmkPair<tableaus::verner98, verner98_control>;

// The same pairs and controllers in Cayley coordinates R = R_n cay(ŵ)
// (rkmk_chart.hpp): `rkmk-cayley-dp54` … `rkmk-cayley-verner98`.
using RkmkCayleyDp54 = RkmkPair<tableaus::dormand_prince54, dp54_control, CayleyChart>;
using RkmkCayleyVerner65 = RkmkPair<tableaus::verner65, verner65_control, CayleyChart>;
using RkmkCayleyDop853 = RkmkPair<tableaus::dop853, dop853_control, CayleyChart>;
using RkmkCayleyVerner87 = RkmkPair<tableaus::verner87, dop853_control, CayleyChart>;
using RkmkCayleyVerner98 = RkmkPair<tableaus::verner98, verner98_control, CayleyChart>;

/// Every adaptive RKMK scheme, for the generic tests (tests/test_stated_orders.cpp
/// checks that the registry has no other).
using RkmkPairs = std::tuple<RkmkDp54, RkmkVerner65, RkmkDop853, RkmkVerner87, RkmkVerner98, RkmkCayleyDp54,
                             RkmkCayleyVerner65, RkmkCayleyDop853, RkmkCayleyVerner87, RkmkCayleyVerner98>;

}  // namespace lgi::integrators
