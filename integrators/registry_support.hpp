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
