// Registry lines for the schemes on T³ × ℝ³ (the Cardan top, docs/cardan.md §5):
// cardan-midpoint, cardan-dg, cardan-rk4, cardan-dp54.
#include "integrators/torus/torus_explicit.hpp"
#include "integrators/torus/torus_implicit.hpp"
#include "integrators/torus/torus_registry.hpp"

namespace lgi::integrators::torus {

const std::vector<TorusSchemeInfo>& torus_scheme_registry() {
  static const std::vector<TorusSchemeInfo> registry = [] {
    const std::string newton = "Newton, iteration matrix I - h/2 Df (central differences), to 1e-15 (scaled)";
    std::vector<TorusSchemeInfo> r;
    r.push_back(torus_entry<TorusMidpoint>("cardan-midpoint", "symplectic; " + newton));
    r.push_back(torus_entry<TorusDiscreteGradient>("cardan-dg", "energy to the solver's tolerance; " + newton));
    r.push_back(torus_entry<TorusRk4>("cardan-rk4", "explicit baseline"));
    r.push_back(torus_entry<TorusDp54>("cardan-dp54", "adaptive, for references"));
    return r;
  }();
  return registry;
}

const TorusSchemeInfo* find_torus_scheme(std::string_view name) {
  for (const auto& s : torus_scheme_registry())
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace lgi::integrators::torus
