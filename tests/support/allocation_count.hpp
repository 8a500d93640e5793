#pragma once
// The program's heap allocation count, for the tests that check "no allocation
// per step". experiments/analysis/allocation_counter.hpp counts them by
// replacing the global operator new, so it may be in one unit of a program
// only; in lgi_tests (all test files in one executable) that unit is
// support/allocation_counter.cpp, and the test files read the count here.
namespace lgi::testing {

/// The number of heap allocations so far (allocation_counter.hpp's counted_allocations).
long counted_allocations();

}  // namespace lgi::testing
