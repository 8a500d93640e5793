// Registry lines for Verner's most efficient 8(7) and 9(8) pairs on RKMK
// (rkmk_adaptive.hpp). Kept apart from registry_lie_group_runge_kutta.cpp:
// each flattened step is large, and two units compile in parallel.
#include "integrators/registry_support.hpp"
#include "integrators/rkmk_adaptive.hpp"

namespace lgi::integrators {

void add_verner_high_order_pairs(std::vector<SchemeInfo>& r) {
  add_scheme<RkmkVerner87>(r, {.name = "rkmk-verner87",
                               .family = "RKMK",
                               .notes = "adaptive (--tol), Verner's most efficient 8(7) pair; output times landed on; PI "
                                        "controller"});
  add_scheme<RkmkVerner98>(r, {.name = "rkmk-verner98",
                               .family = "RKMK",
                               .notes = "adaptive (--tol), Verner's most efficient 9(8) pair; output times landed on; PI "
                                        "controller"});
}

}  // namespace lgi::integrators
