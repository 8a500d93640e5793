// Registry lines for: split-exact.
#include "integrators/registry_support.hpp"

namespace lgi::integrators {

void add_splitting_schemes(std::vector<SchemeInfo>& /*registry*/) {}

}  // namespace lgi::integrators
