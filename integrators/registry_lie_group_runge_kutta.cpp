// Registry lines for the exact flow and the explicit Lie-group Runge–Kutta
// family (RKMK, Crouch–Grossman, commutator-free).
#include "integrators/commutator_free.hpp"
#include "integrators/crouch_grossman.hpp"
#include "integrators/exact_free_flow.hpp"
#include "integrators/registry_support.hpp"
#include "integrators/rkmk.hpp"
#include "integrators/rkmk_adaptive.hpp"

namespace lgi::integrators {

void add_lie_group_runge_kutta_schemes(std::vector<SchemeInfo>& r) {
  const std::string munthe_kaas =
      "Munthe-Kaas, Appl. Numer. Math. 29 (1999) 115-127; Iserles et al., Acta Numerica 9 (2000) 5.3";
  constexpr SchemeProperties explicit_lie_group{};
  r.push_back({"exact", 0, "exact flow",
               {.symmetric = true, .conserves_energy = true, .conserves_momentum_norm = true,
                .conserves_spatial_momentum = true},
               SceneSupport::free_body_only,
               "Jacobi elliptic functions for Pi; elliptic integral of the third kind for R (Celledoni, Fasso, "
               "Safstrom & Zanna, SIAM J. Sci. Comput. 30 (2008))",
               "free bodies only; evaluated from the initial state at every output time",
               &run_fixed_free_body<ExactFreeFlow>});
  r.push_back({"lie-euler", 1, "RKMK", explicit_lie_group, SceneSupport::any,
               munthe_kaas + "; tableau: explicit Euler", "", &run_fixed<LieEuler>});
  r.push_back({"rkmk2", 2, "RKMK", explicit_lie_group, SceneSupport::any,
               munthe_kaas + "; tableau: Heun (HNW I, Table 1.1)", "", &run_fixed<Rkmk2>});
  r.push_back({"rkmk3", 3, "RKMK", explicit_lie_group, SceneSupport::any,
               munthe_kaas + "; tableau: Kutta's third order (HNW I, Table 1.1)", "", &run_fixed<Rkmk3>});
  r.push_back({"rkmk4", 4, "RKMK", explicit_lie_group, SceneSupport::any,
               munthe_kaas + "; tableau: classical RK4 (HNW I, Table 1.2)", "", &run_fixed<Rkmk4>});
  r.push_back({"rkmk-dp54", 5, "RKMK", {.adaptive = true}, SceneSupport::any,
               munthe_kaas + "; tableau: Dormand & Prince, J. Comput. Appl. Math. 6 (1980)",
               "adaptive (--tol); error estimated on the algebra and in Pi", &run_adaptive<RkmkDp54>});
  r.push_back({"cg3", 3, "Crouch-Grossman", explicit_lie_group, SceneSupport::any,
               "Crouch & Grossman, J. Nonlinear Sci. 3 (1993); Owren & Marthinsen, BIT 39 (1999)", "",
               &run_fixed<Cg3>});
  r.push_back({"cg4a", 4, "Crouch-Grossman", explicit_lie_group, SceneSupport::any,
               "Jackiewicz, Marthinsen & Owren, Adv. Comput. Math. 13 (2000), App. A Ex. 1", "5 stages",
               &run_fixed<Cg4a>});
  r.push_back({"cf4", 4, "commutator-free", explicit_lie_group, SceneSupport::any,
               "Celledoni, Marthinsen & Owren, Future Gener. Comput. Syst. 19 (2003)", "two exponentials per step",
               &run_fixed<Cf4>});
}

}  // namespace lgi::integrators
