#include "integrators/registry/registry.hpp"

#include <stdexcept>
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
  r.reserve(r.size() + 64);  // out-of-tree registrations keep pointers into the table valid
  return r;
}

std::vector<SchemeInfo>& mutable_registry() {
  static std::vector<SchemeInfo> registry = build_registry();
  return registry;
}

}  // namespace

const std::vector<SchemeInfo>& scheme_registry() { return mutable_registry(); }

void register_scheme(SchemeInfo scheme) {
  if (scheme.name.empty()) throw std::invalid_argument("register_scheme: the scheme has no name");
  if (!scheme.run) throw std::invalid_argument("register_scheme: scheme '" + scheme.name + "' has no run function");
  if (find_scheme(scheme.name))
    throw std::invalid_argument("register_scheme: a scheme named '" + scheme.name + "' is already registered");
  mutable_registry().push_back(std::move(scheme));
}

const SchemeInfo* find_scheme(std::string_view name) {
  for (const auto& s : scheme_registry())
    if (s.name == name) return &s;
  return nullptr;
}

std::string support_refusal(SceneSupport support, const system::AnyModel& model) {
  switch (support) {
    case SceneSupport::any:
      return {};
    case SceneSupport::free_body_only:
      if (!std::holds_alternative<system::FreeBody>(model))
        return "needs a free body (no torque term: no [gravity], [spring], [drive] or [magnetic])";
      return {};
    case SceneSupport::conservative_only:
      if (!std::visit([](const auto& m) { return m.is_conservative(); }, model))
        return "needs torques from a potential (no damping, no [drive])";
      return {};
    case SceneSupport::cardan_only:
      return "integrates the Cardan top on T^3 and needs a scene with a [suspension] table (docs/cardan.md)";
  }
  return {};
}

std::string unsupported_reason(const SchemeInfo& scheme, const system::AnyModel& model) {
  const std::string why = support_refusal(scheme.support, model);
  return why.empty() ? why : "scheme '" + scheme.name + "' " + why;
}

}  // namespace lgi::integrators
