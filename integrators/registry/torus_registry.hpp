#pragma once
// Registry lines for the schemes on T³ × ℝ³ (the Cardan top, docs/cardan.md
// §5): the same SchemeInfo records as the SO(3) registry, read from each
// scheme's facts, with run functions on the Cardan model. They run on the
// one time loop (stepper_loop.hpp, on system::TorusState), so output times,
// events and checkpoints work as on SO(3) × ℝ³. tests/test_stated_orders.cpp
// and tests/test_cardan_schemes.cpp check every entry's order and claims;
// `lgi simulate`, `long-time` and `sweep` run them on scenes with a
// [suspension] table.
#include <string>

#include "integrators/registry/registry.hpp"
#include "integrators/core/stepper_loop.hpp"
#include "integrators/system/cardan.hpp"

namespace lgi::integrators::torus {

/// Runs Scheme with the fixed-step or the adaptive loop, as its facts say.
template <SchemeWithFacts Scheme>
RunStats run_cardan_scheme(const system::CardanTop& model, system::TorusState& state, const TorusRunConfig& cfg,
                           TorusObserver& observer) {
  if constexpr (Scheme::facts.properties.adaptive) {
    Scheme scheme(cfg.tol);
    return integrate_adaptive(scheme, model, state, cfg, observer);
  } else {
    Scheme scheme;
    return integrate_fixed(scheme, model, state, cfg, observer);
  }
}

/// The fixed-step loop on the scheme's step(): for an adaptive scheme, its
/// propagated solution on a fixed grid (order checks).
template <SchemeWithFacts Scheme>
RunStats run_cardan_scheme_fixed(const system::CardanTop& model, system::TorusState& state, const TorusRunConfig& cfg,
                                 TorusObserver& observer) {
  Scheme scheme;
  return integrate_fixed(scheme, model, state, cfg, observer);
}

/// The registry line of Scheme (support cardan_only, no SO(3) run function).
template <SchemeWithFacts Scheme>
SchemeInfo cardan_entry(std::string name, std::string notes) {
  constexpr SchemeFacts f = Scheme::facts;
  std::string reference = f.reference;
  if (*f.tableau) reference += std::string("; tableau: ") + f.tableau;
  SchemeProperties properties = f.properties;
  properties.dense_output = integrators::detail::has_dense_output<Scheme, system::CardanTop>;
  return {.name = std::move(name),
          .order = f.order,
          .family = "Cardan (T^3)",
          .properties = properties,
          .support = SceneSupport::cardan_only,
          .reference = std::move(reference),
          .notes = std::move(notes),
          .run = nullptr,
          .resumable = resumable_scheme<Scheme, system::CardanTop, f.properties.adaptive>(),
          .run_cardan = &run_cardan_scheme<Scheme>,
          .run_cardan_fixed = &run_cardan_scheme_fixed<Scheme>};
}

}  // namespace lgi::integrators::torus
