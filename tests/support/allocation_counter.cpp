// The one unit of lgi_tests that replaces the global operator new (counting
// every heap allocation of the program); support/allocation_count.hpp.
#include "experiments/analysis/allocation_counter.hpp"
#include "allocation_count.hpp"

namespace lgi::testing {

long counted_allocations() { return experiments::verification::counted_allocations(); }

}  // namespace lgi::testing
