// Windowed sums of frequency analysis (windowed_sums.hpp). The exponentials
// e^{−iωτ_i} advance by one complex multiplication per sample and are recomputed
// exactly every 256 samples, so the phase error stays at a few ulps over any run.
#include "experiments/analysis/frequency/windowed_sums.hpp"

#include <algorithm>

#include "experiments/analysis/frequency/hann_window.hpp"
#include "experiments/analysis/frequency/naff.hpp"  // NaffStopped

namespace lgi::experiments::frequency {
namespace {

constexpr std::size_t reseed = 256;
constexpr std::size_t stop_every = std::size_t{1} << 16;  // samples between two reads of the stop flag

/// Calls visit(i, e^{−iωτ_i}) for every sample, in order.
template <class Visit>
void for_each_exponential(const WindowedGrid& grid, double omega, Visit&& visit) {
  const Complex step = std::polar(1.0, -omega * grid.dt);
  for (std::size_t start = 0; start < grid.n; start += reseed) {
    if (start % stop_every == 0) check_stop(grid);
    Complex e = std::polar(1.0, -omega * grid.tau(start));
    const std::size_t end = std::min(grid.n, start + reseed);
    for (std::size_t i = start; i < end; ++i, e *= step) visit(i, e);
  }
}

}  // namespace

void check_stop(const WindowedGrid& grid) {
  if (grid.stop && grid.stop->load(std::memory_order_relaxed)) throw NaffStopped();
}

WindowedGrid windowed_grid(std::size_t n, double dt, int p) {
  WindowedGrid grid;
  grid.n = n;
  grid.dt = dt;
  grid.weight = hann_window(n, p);
  const double scale = 1.0 / static_cast<double>(n - 1);
  for (double& w : grid.weight) w *= scale;
  grid.weight.front() *= 0.5;
  grid.weight.back() *= 0.5;
  for (const double w : grid.weight) grid.mass += w;
  return grid;
}

ProjectionSums projection_sums(const WindowedGrid& grid, const std::vector<Complex>& g, double omega) {
  ProjectionSums s;
  for_each_exponential(grid, omega, [&](std::size_t i, Complex e) {
    const Complex term = grid.weight[i] * g[i] * e;
    s.value += term;
    s.derivative += Complex(0.0, -grid.tau(i)) * term;
  });
  return s;
}

ProjectionSums window_sums(const WindowedGrid& grid, double omega) {
  ProjectionSums s;
  for_each_exponential(grid, omega, [&](std::size_t i, Complex e) {
    const Complex term = grid.weight[i] * e;
    s.value += term;
    s.derivative += Complex(0.0, -grid.tau(i)) * term;
  });
  return s;
}

void add_exponential(const WindowedGrid& grid, Complex c, double omega, std::vector<Complex>& a) {
  // conj(e^{−iωτ}) = e^{iωτ}
  for_each_exponential(grid, omega, [&](std::size_t i, Complex e) { a[i] += c * std::conj(e); });
}

}  // namespace lgi::experiments::frequency
