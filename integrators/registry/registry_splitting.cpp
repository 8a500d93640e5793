// Registry lines for: split-exact, split-axes, split-symmetric.
#include "integrators/registry/registry_support.hpp"
#include "integrators/schemes/split_axes.hpp"
#include "integrators/schemes/split_symmetric.hpp"
#include "integrators/schemes/splitting.hpp"

namespace lgi::integrators {

void add_splitting_schemes(std::vector<SchemeInfo>& r) {
  add_scheme<SplitExact>(
      r, {.name = "split-exact",
          .family = "splitting",
          .notes = "half kick, exact free flow, half kick; exact for a free body; kicks solved exactly (a damper "
                   "as a linear ODE, a drive at frozen time); symplectic only without damper or drive"});
  add_compositions_and_processed<SplitExact>(r);
  add_scheme<SplitAxes>(
      r, {.name = "split-axes",
          .family = "splitting",
          .notes = "the kinetic energy split into the three principal-axis terms, each flow a plane rotation; "
                   "smallest moment outermost, largest in the middle beside split-exact's kick; symplectic only "
                   "without damper or drive"});
  add_compositions_and_processed<SplitAxes>(r);
  add_scheme<SplitSymmetric>(
      r, {.name = "split-symmetric",
          .family = "splitting",
          .notes = "the kinetic energy split into a symmetric top (moments I_m, I_m, I_l: two rotations) and a "
                   "remainder about the axis of the smallest moment; exact free flow for two equal moments; "
                   "split-exact's kick; symplectic only without damper or drive"});
  add_compositions_and_processed<SplitSymmetric>(r);
}

}  // namespace lgi::integrators
