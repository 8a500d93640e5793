// Registry lines for: rkmk-gauss2, rkmk-gauss4, the L-stable scheme (rkmk-radau5).
#include "integrators/implicit_rkmk.hpp"
#include "integrators/registry_support.hpp"

namespace lgi::integrators {

void add_implicit_schemes(std::vector<SchemeInfo>& r) {
  const std::string munthe_kaas =
      "Munthe-Kaas, Appl. Numer. Math. 29 (1999) 115-127; Iserles et al., Acta Numerica 9 (2000) 5.3";
  const std::string newton =
      "Newton with the analytic Jacobian (simplified, refreshed when the contraction exceeds 0.25), "
      "to 1e-15 (scaled)";
  // Gauss conserves the quadratic invariants |Pi|^2 and H of the decoupled free-body Euler equations.
  constexpr SchemeProperties gauss{.symmetric = true, .conserves_momentum_norm = true, .implicit = true};
  r.push_back({"rkmk-gauss2", 2, "implicit RKMK", gauss, SceneSupport::any,
               munthe_kaas + "; tableau: Gauss-Legendre s = 1, implicit midpoint (Hairer & Wanner, Solving ODEs II, "
                             "IV.5, Table 5.1)",
               "A-stable; free body: |Pi| and energy conserved; " + newton, &run_fixed<RkmkGauss2>});
  add_compositions<RkmkGauss2>(r, r.back());
  r.push_back({"rkmk-gauss4", 4, "implicit RKMK", gauss, SceneSupport::any,
               munthe_kaas + "; chart centred at the step midpoint (Zanna, Engo & Munthe-Kaas, BIT 41 (2001) "
                             "395-421); tableau: Gauss-Legendre s = 2 (Hairer & Wanner, Solving ODEs II, IV.5, "
                             "Table 5.2)",
               "A-stable; free body: |Pi| and energy conserved; " + newton, &run_fixed<RkmkGauss4>});
  r.push_back({"rkmk-radau5", 5, "implicit RKMK", {.implicit = true}, SceneSupport::any,
               munthe_kaas + "; tableau: Radau IIA s = 3 (Hairer & Wanner, Solving ODEs II, IV.5, Table 5.6)",
               "L-stable, stiffly accurate (for stiff scenes); " + newton, &run_fixed<RkmkRadau5>});
}

}  // namespace lgi::integrators
