// Registry lines for: split-exact.
#include "integrators/registry_support.hpp"
#include "integrators/splitting.hpp"

namespace lgi::integrators {

void add_splitting_schemes(std::vector<SchemeInfo>& r) {
  add_scheme<SplitExact>(
      r, {.name = "split-exact",
          .family = "splitting",
          .notes = "half kick, exact free flow, half kick; exact for a free body; kicks solved exactly (a damper "
                   "as a linear ODE, a drive at frozen time); symplectic only without damper or drive"});
  add_compositions<SplitExact>(r, r.back());
}

}  // namespace lgi::integrators
