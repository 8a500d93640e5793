#pragma once
// The step of NAFF that finds one frequency (docs/frequency_analysis.md §2;
// Laskar, Icarus 88 (1990) 266): the ω that maximises the windowed projection
// of the residual r on e^{iωτ}, found coarsely as the largest bin of an FFT
// (zero-padded to at least 2n, bins π/T apart for a run of length T), then
// by Brent's method within ±1 bin, then to full precision as the zero of
// the projection's derivative (analytic, windowed_sums.hpp), which Brent's
// method on the value alone cannot give (it stops at √ε relative).
#include <vector>

#include "experiments/analysis/frequency/windowed_sums.hpp"

namespace lgi::experiments::frequency {

/// The squared norm of r's windowed projection at ω ≥ 0. For a complex signal, on e^{iωτ}:
/// |⟨r, e^{iωτ}⟩|² / ⟨1, 1⟩. For a real signal (r real), on the span of e^{±iωτ} (the cosine and
/// the sine at ω), which removes the bias of the mirror peak at −ω.
double projection_power(const WindowedGrid& grid, const std::vector<Complex>& r, double omega, bool real_signal);

/// The frequency of r's largest projection: over ω > 0 for a real signal, over all ω for a complex one.
double strongest_frequency(const WindowedGrid& grid, const std::vector<Complex>& r, bool real_signal);

}  // namespace lgi::experiments::frequency
