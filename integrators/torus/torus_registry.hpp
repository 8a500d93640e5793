#pragma once
// The schemes on T³ × ℝ³ for the Cardan top (docs/cardan.md §5): name,
// order, properties and reference read from each scheme's facts, as in the
// SO(3) registry (integrators/registry_support.hpp), and a run function on
// the Cardan model. tests/test_cardan_schemes.cpp checks every entry's order
// and claims; `lgi simulate` runs them on scenes with a [suspension] table.
#include <string>
#include <string_view>
#include <vector>

#include "integrators/torus/torus_loop.hpp"

namespace lgi::integrators::torus {

using TorusRunFunction = RunStats (*)(const system::CardanTop& model, system::TorusState& state, const RunConfig& cfg,
                                      TorusObserver& observer);

struct TorusSchemeInfo {
  std::string name;
  int order = 0;
  std::string family;
  SchemeProperties properties;
  std::string reference;
  std::string notes;
  TorusRunFunction run = nullptr;
  /// The fixed-step loop on the scheme's step(): for an adaptive scheme, its
  /// propagated solution on a fixed grid (order checks); otherwise `run`.
  TorusRunFunction run_fixed = nullptr;
};

/// Runs Scheme with the fixed-step or the adaptive loop, as its facts say.
template <SchemeWithFacts Scheme>
RunStats run_torus_scheme(const system::CardanTop& model, system::TorusState& state, const RunConfig& cfg,
                          TorusObserver& observer) {
  if constexpr (Scheme::facts.properties.adaptive) {
    Scheme scheme(cfg.tol);
    return integrate_torus_adaptive(scheme, model, state, cfg, observer);
  } else {
    Scheme scheme;
    return integrate_torus_fixed(scheme, model, state, cfg, observer);
  }
}

template <SchemeWithFacts Scheme>
RunStats run_torus_scheme_fixed(const system::CardanTop& model, system::TorusState& state, const RunConfig& cfg,
                                TorusObserver& observer) {
  Scheme scheme;
  return integrate_torus_fixed(scheme, model, state, cfg, observer);
}

template <SchemeWithFacts Scheme>
TorusSchemeInfo torus_entry(std::string name, std::string notes) {
  constexpr SchemeFacts f = Scheme::facts;
  std::string reference = f.reference;
  if (*f.tableau) reference += std::string("; tableau: ") + f.tableau;
  return {std::move(name), f.order, "Cardan (T^3)", f.properties, std::move(reference), std::move(notes),
          &run_torus_scheme<Scheme>, &run_torus_scheme_fixed<Scheme>};
}

const std::vector<TorusSchemeInfo>& torus_scheme_registry();
/// nullptr if no T³ scheme has that name.
const TorusSchemeInfo* find_torus_scheme(std::string_view name);

}  // namespace lgi::integrators::torus
