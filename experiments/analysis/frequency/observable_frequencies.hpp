#pragma once
// NAFF of each sampled observable and its diffusion index: the records of
// `lgi frequencies` and lgi.frequencies() (experiments/FREQUENCIES.md).
#include <string>
#include <vector>

#include "experiments/analysis/frequency/frequency_diffusion.hpp"
#include "experiments/analysis/frequency/naff.hpp"
#include "experiments/analysis/frequency/observable_series.hpp"

namespace lgi::experiments::frequency {

struct ObservableFrequencies {
  std::string observable;
  NaffResult terms;              // over the whole run
  FrequencyDiffusion diffusion;  // leading frequency on the two halves
};

/// One record per series of `run` (named by `names`, in order); observables that
/// are constant along the run (no term found) get no terms and NaN diffusion.
std::vector<ObservableFrequencies> observable_frequencies(const SampledRun& run, const std::vector<std::string>& names,
                                                          const NaffOptions& options);

}  // namespace lgi::experiments::frequency
