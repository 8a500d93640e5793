#include "integrators/registry.hpp"

#include <variant>

namespace lgi::integrators {
namespace {

std::vector<SchemeInfo> build_registry() {
  std::vector<SchemeInfo> r;
  add_lie_group_runge_kutta_schemes(r);
  add_variational_schemes(r);
  add_energy_momentum_schemes(r);
  add_splitting_schemes(r);
  add_implicit_schemes(r);
  add_baseline_schemes(r);
  return r;
}

}  // namespace

const std::vector<SchemeInfo>& scheme_registry() {
  static const std::vector<SchemeInfo> registry = build_registry();
  return registry;
}

const SchemeInfo* find_scheme(std::string_view name) {
  for (const auto& s : scheme_registry())
    if (s.name == name) return &s;
  return nullptr;
}

std::string unsupported_reason(const SchemeInfo& scheme, const system::AnyModel& model) {
  switch (scheme.support) {
    case SceneSupport::any:
      return {};
    case SceneSupport::free_body_only:
      if (!std::holds_alternative<system::FreeBody>(model))
        return "scheme '" + scheme.name + "' needs a free body (no [gravity], [spring] or [drive])";
      return {};
    case SceneSupport::conservative_only: {
      const bool conservative = std::visit(
          [](const auto& m) {
            using M = std::decay_t<decltype(m)>;
            if constexpr (M::time_dependent) return false;
            else if constexpr (M::template has_term<system::SpringTerm>)
              return m.template term<system::SpringTerm>().damping == 0.0;
            else return true;
          },
          model);
      if (!conservative)
        return "scheme '" + scheme.name + "' needs torques from a potential (no damping, no [drive])";
      return {};
    }
  }
  return {};
}

}  // namespace lgi::integrators
