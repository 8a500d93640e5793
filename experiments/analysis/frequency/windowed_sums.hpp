#pragma once
// The windowed inner products of frequency analysis (docs/frequency_analysis.md §1):
// on n uniform samples with centred times τ_i = (i − (n − 1)/2) dt,
//   ⟨f, g⟩ = Σ_i ω_i f_i conj(g_i),  ω_i = χ_p(i) c_i / (n − 1),
// the trapezoid rule (c_i = 1/2 at the ends, 1 inside) on Laskar's window χ_p
// (hann_window.hpp). Centring the times keeps the window's transform real.
#include <atomic>
#include <complex>
#include <cstddef>
#include <vector>

namespace lgi::experiments::frequency {

using Complex = std::complex<double>;

struct WindowedGrid {
  std::size_t n = 0;
  double dt = 0.0;
  std::vector<double> weight;  // ω_i
  double mass = 0.0;           // Σ ω_i = ⟨1, 1⟩ (1 up to the trapezoid rule's error)
  const std::atomic<bool>* stop = nullptr;  // NaffOptions::stop: every pass reads it (naff.hpp)
  double tau(std::size_t i) const { return (static_cast<double>(i) - 0.5 * static_cast<double>(n - 1)) * dt; }
  double half_span() const { return 0.5 * static_cast<double>(n - 1) * dt; }
};

/// Throws NaffStopped (naff.hpp) if grid.stop is set; every pass over the samples calls it every 2^16.
void check_stop(const WindowedGrid& grid);

/// The grid of n ≥ 2 samples spaced dt with the window of order p ≥ 0.
WindowedGrid windowed_grid(std::size_t n, double dt, int p);

/// ⟨g, e^{iωτ}⟩ = Σ ω_i g_i e^{−iωτ_i} and its derivative in ω, Σ ω_i g_i (−iτ_i) e^{−iωτ_i}.
struct ProjectionSums {
  Complex value{}, derivative{};
};
ProjectionSums projection_sums(const WindowedGrid& grid, const std::vector<Complex>& g, double omega);

/// The same with g = 1: ⟨1, e^{iωτ}⟩ (the window's transform, real up to rounding) and its derivative.
ProjectionSums window_sums(const WindowedGrid& grid, double omega);

/// a_i += c e^{iωτ_i} for every sample (c = −coefficient subtracts a term).
void add_exponential(const WindowedGrid& grid, Complex c, double omega, std::vector<Complex>& a);

}  // namespace lgi::experiments::frequency
