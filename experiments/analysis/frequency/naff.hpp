#pragma once
// NAFF, Laskar's numerical analysis of fundamental frequencies
// (docs/frequency_analysis.md; Laskar, Icarus 88 (1990) 266; Laskar,
// Froeschlé & Celletti, Physica D 56 (1992) 253; Laskar, Physica D 67 (1993) 257):
// a signal sampled at uniform times t0 + i dt is written as a sum of terms
// a_k e^{iω_k t}, found one at a time: the frequency of the largest windowed
// projection of the residual (peak_search.hpp), then the projection of the
// signal on all the terms found so far (Gram–Schmidt: the e^{iω_k t} are not
// orthogonal on a finite window) subtracted. No file I/O.
//
// A real signal f is analysed as f(t) = c + Σ A_k cos(ω_k (t − t0) + φ_k), ω_k > 0:
// each term is the pair e^{±iω_k t}, the constant c a term of its own.
#include <atomic>
#include <complex>
#include <stdexcept>
#include <vector>

namespace lgi::experiments::frequency {

struct NaffOptions {
  int terms = 5;         // terms to find (fewer if the residual is exhausted)
  int window_order = 1;  // p of Laskar's window χ_p (hann_window.hpp); the error decays as T^−(2p+2)
  /// A stop flag (Ctrl-C, lgi frequencies), read every 2^16 samples of each pass over the
  /// series (sums, FFT stages): once set, the analysis throws NaffStopped. Null: never.
  const std::atomic<bool>* stop = nullptr;
};

/// Thrown by the analysis when NaffOptions::stop is set.
struct NaffStopped : std::runtime_error {
  NaffStopped() : std::runtime_error("frequency analysis interrupted by signal") {}
};

struct NaffTerm {
  double frequency = 0.0;  // rad per unit time (> 0 for a real signal; signed for a complex one)
  double amplitude = 0.0;  // A_k (real signal), |a_k| (complex)
  double phase = 0.0;      // φ_k at the first sample, in (−π, π]: a_k = |a_k| e^{iφ_k} e^{iω_k t0} for a complex signal
};

struct NaffResult {
  std::vector<NaffTerm> terms;  // by decreasing amplitude
  std::complex<double> mean{};  // the constant term c (real signal; 0 for a complex one)
};

/// Throws std::invalid_argument unless f has at least 16 samples, dt > 0, terms ≥ 1 and 0 ≤ window_order ≤ 8.
NaffResult naff_real(const std::vector<double>& f, double dt, const NaffOptions& options);
NaffResult naff_complex(const std::vector<std::complex<double>>& f, double dt, const NaffOptions& options);

}  // namespace lgi::experiments::frequency
