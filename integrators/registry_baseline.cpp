// Registry lines for: COORDS/STEPPER baselines through Boost.Odeint.
#include "integrators/registry_support.hpp"

namespace lgi::integrators {

void add_baseline_schemes(std::vector<SchemeInfo>& /*registry*/) {}

}  // namespace lgi::integrators
