// Registry lines for Verner's most efficient 8(7) and 9(8) pairs on RKMK
// (rkmk_adaptive.hpp). Kept apart from registry_lie_group_runge_kutta.cpp:
// each flattened step is large, and two units compile in parallel.
#include "integrators/registry/registry_support.hpp"
#include "integrators/schemes/rkmk_adaptive.hpp"

// The pairs' order conditions are checked in tableaus/pair_checks_verner87.cpp
// and pair_checks_verner98.cpp, each in a unit of its own.

namespace lgi::integrators {

void add_verner_high_order_pairs(std::vector<SchemeInfo>& r) {
  add_scheme<RkmkVerner87>(r, {.name = "rkmk-verner87",
                               .family = "RKMK",
                               .notes = "adaptive (--tol), Verner's most efficient 8(7) pair; dense output of order 8; PI "
                                        "controller"});
  add_scheme<RkmkVerner98>(r, {.name = "rkmk-verner98",
                               .family = "RKMK",
                               .notes = "adaptive (--tol), Verner's most efficient 9(8) pair; dense output of order 9; PI "
                                        "controller"});
}

}  // namespace lgi::integrators
