#pragma once
// Whether a test should print its measurements (LGI_TEST_VERBOSE set).
#include <cstdlib>

namespace lgi::testing {

inline bool verbose() { return std::getenv("LGI_TEST_VERBOSE") != nullptr; }

}  // namespace lgi::testing
