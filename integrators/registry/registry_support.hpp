#pragma once
// Registration from a scheme type's own facts (scheme_facts.hpp): a registry
// line gives the name, the family and notes; order, properties, scene support
// and references are read from Scheme::facts, and the run function is chosen
// from them (fixed step or adaptive; the free body only where so stated), as
// is the lane mode of a scheme whose facts declare a lane kernel.
#include <string>
#include <type_traits>
#include <variant>

#include "integrators/schemes/composition.hpp"
#include "integrators/ensemble/lane_mode_of.hpp"
#include "integrators/schemes/processed_composition.hpp"
#include "integrators/registry/registry.hpp"

namespace lgi::integrators {

/// What a registry line adds to a scheme's facts.
struct SchemeEntry {
  std::string name;
  std::string family;
  std::string notes{};
  std::string base_scheme{};
};

/// Runs Scheme on the scene's model, dispatched once per run. A scene outside
/// the scheme's support is refused here too: a caller that skipped
/// unsupported_reason() gets a failed run with the reason, not a trajectory
/// that silently ignores a drive or a damper.
template <SchemeWithFacts Scheme>
RunStats run_scheme(const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  constexpr SchemeFacts facts = Scheme::facts;
  if (std::string why = support_refusal(facts.support, model); !why.empty()) {
    RunStats refused;
    refused.ok = false;
    refused.status = "the scheme " + why;
    return refused;
  }
  return std::visit(
      [&](const auto& m) -> RunStats {
        using M = std::decay_t<decltype(m)>;
        if constexpr (facts.support == SceneSupport::free_body_only && !std::is_same_v<M, system::FreeBody>) {
          return {};  // refused above; not instantiated for torques
        } else if constexpr (facts.properties.adaptive) {
          Scheme scheme(cfg.tol);
          return integrate_adaptive(scheme, m, state, cfg, observer);
        } else {
          Scheme scheme;
          return integrate_fixed(scheme, m, state, cfg, observer);
        }
      },
      model);
}

/// The registry line of Scheme.
template <SchemeWithFacts Scheme>
void add_scheme(std::vector<SchemeInfo>& registry, const SchemeEntry& entry) {
  constexpr SchemeFacts facts = Scheme::facts;
  std::string reference = facts.reference;
  if (*facts.tableau) reference += std::string(reference.empty() ? "" : "; ") + "tableau: " + facts.tableau;
  SchemeProperties properties = facts.properties;
  properties.dense_output = detail::has_dense_output<Scheme, system::FreeBody>;
  registry.push_back({.name = entry.name,
                      .order = facts.order,
                      .family = entry.family,
                      .properties = properties,
                      .support = facts.support,
                      .reference = reference,
                      .notes = entry.notes,
                      .run = &run_scheme<Scheme>,
                      .order_with_torque = facts.order_with_torque,
                      .base_scheme = entry.base_scheme,
                      // a processed composition's loop state is not the trajectory's between outputs
                      .locates_events = !detail::has_observable_state<Scheme, system::FreeBody>,
                      .resumable = resumable_scheme<Scheme, system::FreeBody, facts.properties.adaptive>(),
                      .lanes = ensemble::lane_mode_of<Scheme>()});
}

/// The registry line of one composition of `base`: BASE@NAME, in the family
/// "composition of BASE", its notes `what` and then the base's.
template <SchemeWithFacts Composed>
void add_composed(std::vector<SchemeInfo>& registry, const SchemeInfo& base, const char* name,
                  const std::string& what) {
  add_scheme<Composed>(registry, {.name = base.name + "@" + name,
                                  .family = "composition of " + base.name,
                                  .notes = what + (base.notes.empty() ? "" : "; " + base.notes),
                                  .base_scheme = base.name});
  registry.back().reference += "; base: " + base.name;
}

/// Registers BASE@yoshida4, @suzuki4, @kahan-li6 and @kahan-li8 for a
/// symmetric scheme of order 2 (Composition checks that at compile time).
template <SchemeWithFacts Base>
void add_compositions(std::vector<SchemeInfo>& registry, const SchemeInfo& base_entry) {
  // A copy: base_entry is usually registry.back(), which push_back may move.
  const SchemeInfo base = base_entry;
  auto add = [&]<const auto& Coefficients>() {
    add_composed<Composition<Base, Coefficients>>(registry, base, Coefficients.name,
                                                  std::to_string(Coefficients.stages) + " stages of " + base.name);
  };
  add.template operator()<tableaus::yoshida4>();
  add.template operator()<tableaus::suzuki4>();
  add.template operator()<tableaus::kahan_li6>();
  add.template operator()<tableaus::kahan_li8>();
}

/// Registers BASE@bcm-processed6 and BASE@bcm-processed8 for a symmetric
/// scheme of order 2 (processed_composition.hpp).
template <SchemeWithFacts Base>
void add_processed_compositions(std::vector<SchemeInfo>& registry, const SchemeInfo& base_entry) {
  const SchemeInfo base = base_entry;  // a copy, as in add_compositions
  auto add = [&]<const auto& Coefficients>() {
    add_composed<ProcessedComposition<Base, Coefficients>>(
        registry, base, Coefficients.name,
        std::to_string(Coefficients.stages) + " stages of " + base.name + " a step, a " +
            std::to_string(Coefficients.processor_stages) +
            "-stage processor (Blanes-Casas-Murua) at the start and at each output; no events");
  };
  add.template operator()<tableaus::bcm_processed6>();
  add.template operator()<tableaus::bcm_processed8>();
}

/// Both for the base just registered (registry.back()).
template <SchemeWithFacts Base>
void add_compositions_and_processed(std::vector<SchemeInfo>& registry) {
  const SchemeInfo base = registry.back();
  add_compositions<Base>(registry, base);
  add_processed_compositions<Base>(registry, base);
}

}  // namespace lgi::integrators
