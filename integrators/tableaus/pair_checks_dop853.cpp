// Every compile-time check of the DOP853 pair (embedded_pairs.hpp, pair_checks_out):
// its order conditions, those of its embedded weights and of its interpolant.
// Checked once, in this unit of its own, rather than in every unit that
// includes dop853.hpp: the constant evaluation over the extended tableau's
// stages is a large part of such a unit's compile time (docs/performance.md §8).
#include "integrators/tableaus/dop853.hpp"

static_assert(lgi::tableaus::pair_checks_out<lgi::tableaus::dop853>(),
              "DOP853: a coefficient does not satisfy its order conditions");
