// Registry lines for: split-exact.
#include "integrators/registry_support.hpp"
#include "integrators/splitting.hpp"

namespace lgi::integrators {

void add_splitting_schemes(std::vector<SchemeInfo>& r) {
  // Conservation flags mean "exact where the quantity is an invariant of the scene":
  // |Pi| and m for a free body (the scheme is then the exact flow), Pi.Gamma for a
  // heavy top (kick along Gamma x m g chi, free flow conserves m). The energy of a
  // torqued scene is not conserved exactly (symplectic: bounded, no drift).
  r.push_back({"split-exact", 2, "splitting",
               // |Π| and m are not claimed: the per-step elliptic-function flow keeps them
               // only to ~1e-12 over 1e5 steps (measured 1.3e-12 and 9.7e-12), not to round-off.
               {.symplectic = true, .symmetric = true, .conserves_vertical_momentum = true},
               SceneSupport::any,
               "Celledoni, Fasso, Safstrom & Zanna, SIAM J. Sci. Comput. 30 (2008) 2084-2112 (Strang splitting "
               "with the exact free flow)",
               "half kick, exact free flow, half kick; exact for a free body; kicks solved exactly (a damper "
               "as a linear ODE, a drive at frozen time); symplectic only without damper or drive",
               &run_fixed<SplitExact>});
  add_compositions<SplitExact>(r, r.back());
}

}  // namespace lgi::integrators
