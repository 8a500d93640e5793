// Registry lines for: simo-wong.
#include "integrators/registry_support.hpp"

namespace lgi::integrators {

void add_energy_momentum_schemes(std::vector<SchemeInfo>& /*registry*/) {}

}  // namespace lgi::integrators
