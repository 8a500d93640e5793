// Registry lines for the schemes on T³ × ℝ³ (the Cardan top, docs/cardan.md §5):
// cardan-midpoint, cardan-dg, cardan-rk4, cardan-dp54.
#include "integrators/schemes/torus_explicit.hpp"
#include "integrators/schemes/torus_implicit.hpp"
#include "integrators/registry/torus_registry.hpp"

namespace lgi::integrators {

const std::vector<SchemeInfo>& cardan_scheme_registry() {
  static const std::vector<SchemeInfo> registry = [] {
    using namespace torus;
    const std::string newton = "Newton, iteration matrix I - h/2 Df (central differences), to 1e-15 (scaled)";
    std::vector<SchemeInfo> r;
    r.push_back(cardan_entry<TorusMidpoint>("cardan-midpoint", "symplectic; " + newton));
    r.push_back(cardan_entry<TorusDiscreteGradient>("cardan-dg", "energy to the solver's tolerance; " + newton));
    r.push_back(cardan_entry<TorusRk4>("cardan-rk4", "explicit baseline"));
    r.push_back(cardan_entry<TorusDp54>("cardan-dp54", "adaptive, for references"));
    return r;
  }();
  return registry;
}

const SchemeInfo* find_cardan_scheme(std::string_view name) {
  for (const auto& s : cardan_scheme_registry())
    if (s.name == name) return &s;
  return nullptr;
}

const char* state_space_name(const SchemeInfo& scheme) {
  return scheme.support == SceneSupport::cardan_only ? StateSpace<system::TorusState>::name
                                                      : StateSpace<system::State>::name;
}

}  // namespace lgi::integrators
