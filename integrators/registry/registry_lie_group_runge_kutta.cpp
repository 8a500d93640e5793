// Registry lines for the exact flow and the explicit Lie-group Runge–Kutta
// family (RKMK, Crouch–Grossman, commutator-free). Orders, properties and
// references come from each scheme's facts.
#include "integrators/schemes/commutator_free.hpp"
#include "integrators/schemes/crouch_grossman.hpp"
#include "integrators/schemes/exact_free_flow.hpp"
#include "integrators/registry/registry_support.hpp"
#include "integrators/schemes/rkmk.hpp"
#include "integrators/schemes/rkmk_adaptive.hpp"

namespace lgi::integrators {

void add_lie_group_runge_kutta_schemes(std::vector<SchemeInfo>& r) {
  add_scheme<ExactFreeFlow>(
      r, {.name = "exact",
          .family = "exact flow",
          .notes = "free bodies only; evaluated from the initial state at every output time"});
  add_scheme<LieEuler>(r, {.name = "lie-euler", .family = "RKMK"});
  add_scheme<Rkmk2>(r, {.name = "rkmk2", .family = "RKMK"});
  add_scheme<Rkmk3>(r, {.name = "rkmk3", .family = "RKMK"});
  add_scheme<Rkmk4>(r, {.name = "rkmk4", .family = "RKMK"});
  add_scheme<RkmkCayley4>(r, {.name = "rkmk-cayley4", .family = "RKMK", .notes = "classical RK4 in Cayley coordinates"});
  add_scheme<RkmkDp54>(
      r, {.name = "rkmk-dp54", .family = "RKMK", .notes = "adaptive (--tol); error estimated on the algebra and in Pi"});
  add_scheme<RkmkVerner65>(r, {.name = "rkmk-verner65",
                               .family = "RKMK",
                               .notes = "adaptive (--tol), Verner 6(5) pair; dense output of order 6; PI controller"});
  add_scheme<RkmkDop853>(r, {.name = "rkmk-dop853",
                             .family = "RKMK",
                             .notes = "adaptive (--tol), DOP853 with 8(5,3) estimator; dense output of order 7; PI "
                                      "controller"});
  add_verner_high_order_pairs(r);  // registry_verner_pairs.cpp: a unit of its own, as they are large
  add_cayley_pairs(r);             // registry_cayley_pairs.cpp, for the same reason
  add_scheme<Cg3>(r, {.name = "cg3", .family = "Crouch-Grossman"});
  add_scheme<Cg4a>(r, {.name = "cg4a", .family = "Crouch-Grossman", .notes = "5 stages"});
  add_scheme<Cf4>(r, {.name = "cf4", .family = "commutator-free", .notes = "two exponentials per step"});
}

}  // namespace lgi::integrators
