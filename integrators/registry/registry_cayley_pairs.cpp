// Registry lines for the adaptive RKMK pairs in Cayley coordinates
// (rkmk_chart.hpp, rkmk_adaptive.hpp). A unit of its own: each flattened
// step is large, and the units compile in parallel. The pairs' order
// conditions are checked where their exponential versions are registered.
#include "integrators/registry/registry_support.hpp"
#include "integrators/schemes/rkmk_adaptive.hpp"

namespace lgi::integrators {

void add_cayley_pairs(std::vector<SchemeInfo>& r) {
  constexpr const char* family = "RKMK";
  add_scheme<RkmkCayleyDp54>(r, {.name = "rkmk-cayley-dp54",
                                 .family = family,
                                 .notes = "adaptive (--tol), rkmk-dp54 in Cayley coordinates"});
  add_scheme<RkmkCayleyVerner65>(r, {.name = "rkmk-cayley-verner65",
                                     .family = family,
                                     .notes = "adaptive (--tol), rkmk-verner65 in Cayley coordinates; dense output "
                                              "of order 6"});
  add_scheme<RkmkCayleyDop853>(r, {.name = "rkmk-cayley-dop853",
                                   .family = family,
                                   .notes = "adaptive (--tol), rkmk-dop853 in Cayley coordinates; dense output of "
                                            "order 7"});
  add_scheme<RkmkCayleyVerner87>(r, {.name = "rkmk-cayley-verner87",
                                     .family = family,
                                     .notes = "adaptive (--tol), rkmk-verner87 in Cayley coordinates; dense output "
                                              "of order 8"});
  add_scheme<RkmkCayleyVerner98>(r, {.name = "rkmk-cayley-verner98",
                                     .family = family,
                                     .notes = "adaptive (--tol), rkmk-verner98 in Cayley coordinates; dense output "
                                              "of order 9"});
}

}  // namespace lgi::integrators
