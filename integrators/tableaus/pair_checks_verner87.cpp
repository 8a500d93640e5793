// Every compile-time check of the Verner 8(7) pair (embedded_pairs.hpp, pair_checks_out):
// its order conditions, those of its embedded weights and of its interpolant.
// Checked once, in this unit of its own, rather than in every unit that
// includes verner87.hpp: the constant evaluation over the extended tableau's
// stages is a large part of such a unit's compile time (docs/performance.md §8).
#include "integrators/tableaus/verner87.hpp"

static_assert(lgi::tableaus::pair_checks_out<lgi::tableaus::verner87>(),
              "Verner 8(7): a coefficient does not satisfy its order conditions");
