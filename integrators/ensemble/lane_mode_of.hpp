#pragma once
// The lane mode of a scheme type (lane_mode.hpp), from its facts: add_scheme
// (registry_support.hpp) stores it in the scheme's registry entry. A scheme
// whose facts declare a lane kernel gets the ensemble loop instantiated with
// its own scalar hooks (ensemble_loop.hpp) and, for the DMV kernel, itself as
// the scalar scheme behind each lane (dmv_fallback.hpp); one facts field is
// all a scheme states (docs/extending.md, "Adding a lane kernel").
#include <variant>

#include "integrators/ensemble/dmv_fallback.hpp"
#include "integrators/ensemble/ensemble_loop.hpp"
#include "integrators/ensemble/lane_mode.hpp"
#include "integrators/core/scheme_facts.hpp"

namespace lgi::integrators::ensemble {

/// integrate_fixed_ensemble with Scheme's hooks, dispatched once on the model (RunLanes).
template <class Scheme>
void run_lanes(EnsembleStepper& e, const system::AnyModel& model, std::span<State> states, const RunConfig& cfg,
               std::span<Observer* const> observers, std::span<RunStats> stats, EnsembleWorkspace& ws) {
  std::visit([&](const auto& m) { integrate_fixed_ensemble<Scheme>(e, m, states, cfg, observers, stats, ws); }, model);
}

template <SchemeWithFacts Scheme>
LaneMode lane_mode_of() {
  constexpr LaneKernel kernel = Scheme::facts.lane_kernel;
  if constexpr (kernel == LaneKernel::none) {
    return {};
  } else if constexpr (kernel == LaneKernel::dmv_diagonal) {
    return {.kernel = kernel, .run = &run_lanes<Scheme>, .fallback = &make_dmv_fallback<Scheme>};
  } else {
    return {.kernel = kernel, .run = &run_lanes<Scheme>};
  }
}

}  // namespace lgi::integrators::ensemble
