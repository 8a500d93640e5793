// Registry lines for: rkmk-gauss2, rkmk-gauss4, the L-stable scheme (rkmk-radau5).
#include "integrators/schemes/implicit_rkmk.hpp"
#include "integrators/registry/registry_support.hpp"

namespace lgi::integrators {

void add_implicit_schemes(std::vector<SchemeInfo>& r) {
  const std::string newton =
      "Newton with the analytic Jacobian (simplified, refreshed when the contraction exceeds 0.25), "
      "to 1e-15 (scaled)";
  add_scheme<RkmkGauss2>(r, {.name = "rkmk-gauss2",
                             .family = "implicit RKMK",
                             .notes = "A-stable; free body: |Pi| and energy conserved; " + newton});
  add_compositions<RkmkGauss2>(r, r.back());
  add_scheme<RkmkGauss4>(r, {.name = "rkmk-gauss4",
                             .family = "implicit RKMK",
                             .notes = "A-stable; free body: |Pi| and energy conserved; " + newton});
  add_scheme<RkmkRadau5>(r, {.name = "rkmk-radau5",
                             .family = "implicit RKMK",
                             .notes = "L-stable, stiffly accurate (for stiff scenes); " + newton});
}

}  // namespace lgi::integrators
