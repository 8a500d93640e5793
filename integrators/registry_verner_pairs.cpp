// Registry lines for Verner's most efficient 8(7) and 9(8) pairs on RKMK
// (rkmk_adaptive.hpp). Kept apart from registry_lie_group_runge_kutta.cpp:
// each flattened step is large, and two units compile in parallel.
#include "integrators/registry_support.hpp"
#include "integrators/rkmk_adaptive.hpp"

// Every order condition of the pairs and of their interpolants (embedded_pairs.hpp),
// checked in this one unit: over 21 and 26 stages it takes half a minute of
// constant evaluation, which every unit including the tableaus would repeat.
static_assert(lgi::tableaus::pair_checks_out<lgi::tableaus::verner87>(),
              "Verner 8(7): a coefficient does not satisfy its order conditions");
static_assert(lgi::tableaus::pair_checks_out<lgi::tableaus::verner98>(),
              "Verner 9(8): a coefficient does not satisfy its order conditions");

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
