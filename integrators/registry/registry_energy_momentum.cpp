// Registry lines for: simo-wong.
#include "integrators/registry/registry_support.hpp"
#include "integrators/schemes/simo_wong.hpp"

namespace lgi::integrators {

void add_energy_momentum_schemes(std::vector<SchemeInfo>& r) {
  add_scheme<SimoWong>(
      r, {.name = "simo-wong",
          .family = "energy-momentum",
          .notes = "implicit midpoint on (Pi, Gamma) with a Cayley attitude update; Newton on 3 unknowns; potentials "
                   "by discrete gradients (energy exact), dampers and drives at the midpoint (damped energy decays "
                   "monotonically); refuses steps that rotate by pi or more"});
  add_compositions<SimoWong>(r, r.back());
}

}  // namespace lgi::integrators
