#pragma once
// The observables of one run of a Cardan top (T³ × ℝ³, docs/cardan.md) at uniform
// times, for frequency analysis (experiments/FREQUENCIES.md, "Cardan tops"): a
// fixed-step T³ scheme samples every D/dt steps (the T³ loop has no output times).
#include <atomic>
#include <string>
#include <vector>

#include "experiments/analysis/frequency/observable_series.hpp"
#include "integrators/system/cardan.hpp"
#include "integrators/registry/registry.hpp"

namespace lgi::experiments::frequency {

/// Runs `scheme` (fixed-step) from x0 over [0, K D], K D ≤ t_end, sampling the names of
/// cardan_observable_names() at every multiple of D. Throws std::invalid_argument for an adaptive
/// scheme, a D that is not a whole multiple of dt, fewer than 16 or more than 1e8 samples, or an
/// unknown name. A run that fails (stats.ok false) returns what it sampled.
SampledRun sample_cardan_observables(const system::CardanTop& top, const integrators::SchemeInfo& scheme,
                                     const SamplingSettings& settings, const system::TorusState& x0,
                                     const std::vector<std::string>& names, const std::atomic<bool>* stop);

}  // namespace lgi::experiments::frequency
