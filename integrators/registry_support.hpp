#pragma once
// Helpers for the registry_<family>.cpp files: the RunFunction of a scheme
// type, dispatched once per run on the scene's model.
#include <variant>

#include "integrators/registry.hpp"

namespace lgi::integrators {

/// A fixed-step scheme, default-constructed per run, on any model.
template <class Scheme>
RunStats run_fixed(const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  return std::visit(
      [&](const auto& m) {
        Scheme scheme;
        return integrate_fixed(scheme, m, state, cfg, observer);
      },
      model);
}

/// An adaptive scheme, constructed from the tolerance, on any model.
template <class Scheme>
RunStats run_adaptive(const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  return std::visit(
      [&](const auto& m) {
        Scheme scheme(cfg.tol);
        return integrate_adaptive(scheme, m, state, cfg, observer);
      },
      model);
}

/// A fixed-step scheme that exists only for the free body (the registry's
/// SceneSupport::free_body_only keeps other models away).
template <class Scheme>
RunStats run_fixed_free_body(const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  Scheme scheme;
  return integrate_fixed(scheme, std::get<system::FreeBody>(model), state, cfg, observer);
}

}  // namespace lgi::integrators

#include "integrators/composition.hpp"

namespace lgi::integrators {

/// Registers BASE@yoshida4, @suzuki4, @kahan-li6 and @kahan-li8 for a
/// symmetric scheme of order 2 (the coefficients raise order 2 to 4, 6, 8;
/// they do not do so for other orders, so other bases are refused here).
template <class Base>
void add_compositions(std::vector<SchemeInfo>& registry, const SchemeInfo& base_entry) {
  // A copy: base_entry is usually registry.back(), which push_back may move.
  const SchemeInfo base = base_entry;
  if (!base.properties.symmetric || base.order != 2) return;
  auto add = [&](const auto& coefficients, RunFunction run) {
    SchemeInfo info = base;
    info.name = base.name + "@" + coefficients.name;
    info.order = coefficients.order;
    // A composition of a method that drops to order 2 with torques stays at 2 there.
    info.order_with_torque = base.order_with_torque ? 2 : 0;
    info.family = "composition of " + base.name;
    info.base_scheme = base.name;
    info.reference = std::string(coefficients.citation) + "; base: " + base.name;
    info.notes = std::to_string(coefficients.stages) + " stages of " + base.name +
                 (base.notes.empty() ? "" : "; " + base.notes);
    info.run = run;
    registry.push_back(info);
  };
  add(tableaus::yoshida4, &run_fixed<Composition<Base, tableaus::yoshida4>>);
  add(tableaus::suzuki4, &run_fixed<Composition<Base, tableaus::suzuki4>>);
  add(tableaus::kahan_li6, &run_fixed<Composition<Base, tableaus::kahan_li6>>);
  add(tableaus::kahan_li8, &run_fixed<Composition<Base, tableaus::kahan_li8>>);
}

}  // namespace lgi::integrators
