#pragma once
// Laskar's diffusion index of frequency map analysis (docs/frequency_analysis.md §3;
// Laskar, Physica D 67 (1993) 257): the leading frequency measured on the first
// and on the second half of a run. On a torus both halves give the same
// frequency to NAFF's precision; a chaotic orbit's frequency drifts.
#include <complex>
#include <vector>

#include "experiments/analysis/frequency/naff.hpp"

namespace lgi::experiments::frequency {

struct FrequencyDiffusion {
  double first_half = 0.0, second_half = 0.0;  // the halves' frequencies nearest the whole run's leading one
  double relative_change = 0.0;                // |ν₂ − ν₁| / |ν₁|
  double log10_relative_change = 0.0;          // log10 of it (−inf where the halves agree exactly)
};

/// The halves of the real signal f (samples spaced dt; with an odd count they share the middle
/// sample), each analysed with `options`; `leading` is the whole run's leading frequency.
FrequencyDiffusion frequency_diffusion(const std::vector<double>& f, double dt, const NaffOptions& options,
                                       double leading);
/// The same for a complex signal (signed frequencies).
FrequencyDiffusion frequency_diffusion(const std::vector<std::complex<double>>& f, double dt,
                                       const NaffOptions& options, double leading);

}  // namespace lgi::experiments::frequency
