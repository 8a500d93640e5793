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

/// One record per observable, in order: a real one, or a complex pair "A+iB" analysed as the
/// complex signal A + iB (signed frequencies: the sense of rotation in the (A, B) plane).
/// `run` holds the series of components_of(observables), in that order. An observable that is
/// constant along the run (no term found) gets no terms and NaN diffusion. The observables are
/// analysed on `threads` OpenMP threads (each alone: the records do not depend on the count).
std::vector<ObservableFrequencies> observable_frequencies(const SampledRun& run,
                                                          const std::vector<std::string>& observables,
                                                          const NaffOptions& options, int threads = 1);

}  // namespace lgi::experiments::frequency
