// Registry lines for: simo-wong.
#include "integrators/registry_support.hpp"
#include "integrators/simo_wong.hpp"

namespace lgi::integrators {

void add_energy_momentum_schemes(std::vector<SchemeInfo>& r) {
  r.push_back({"simo-wong", 2, "energy-momentum",
               {.symmetric = true, .conserves_energy = true, .conserves_momentum_norm = true,
                .conserves_spatial_momentum = true, .conserves_vertical_momentum = true, .implicit = true},
               SceneSupport::any,
               "Simo & Wong, Int. J. Numer. Methods Eng. 31 (1991) 19-52; Austin, Krishnaprasad & Wang, "
               "J. Comput. Phys. 107 (1993) 105-117; discrete gradient: Gonzalez, J. Nonlinear Sci. 6 (1996) 449-467",
               "implicit midpoint on (Pi, Gamma) with a Cayley attitude update; Newton on 3 unknowns; springs by a "
               "discrete gradient (energy exact), dampers and drives at the midpoint (damped energy decays "
               "monotonically); refuses steps that rotate by pi or more",
               &run_fixed<SimoWong>});
  add_compositions<SimoWong>(r, r.back());
}

}  // namespace lgi::integrators
