// One frequency of NAFF (peak_search.hpp).
#include "experiments/analysis/frequency/peak_search.hpp"

#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "experiments/analysis/frequency/fft.hpp"

namespace lgi::experiments::frequency {
namespace {

struct PowerSlope {
  double power = 0.0, slope = 0.0;  // the projection power and (a positive multiple of) its derivative
};

/// Real signal: with b = ⟨r, e^{iωτ}⟩, m = ⟨1, 1⟩ and W = ⟨e^{−iωτ}, e^{iωτ}⟩ (real: the times are centred),
/// the projection on span{e^{iωτ}, e^{−iωτ}} has power 2 (m|b|² − W Re b²) / (m² − W²).
PowerSlope power_and_slope(const WindowedGrid& grid, const std::vector<Complex>& r, double omega, bool real_signal) {
  const ProjectionSums b = projection_sums(grid, r, omega);
  const double m = grid.mass;
  if (!real_signal)
    return {std::norm(b.value) / m, std::real(std::conj(b.value) * b.derivative)};
  const ProjectionSums w2 = window_sums(grid, 2.0 * omega);
  const double W = w2.value.real(), dW = 2.0 * w2.derivative.real();
  const double num = m * std::norm(b.value) - W * std::real(b.value * b.value);
  const double dnum = 2.0 * m * std::real(std::conj(b.value) * b.derivative) - dW * std::real(b.value * b.value) -
                      2.0 * W * std::real(b.value * b.derivative);
  const double den = m * m - W * W, dden = -2.0 * W * dW;
  return {2.0 * num / den, dnum * den - num * dden};
}

/// The bin of the largest |FFT| of the windowed residual, as a frequency; `bin` gets the bin width.
double coarse_peak(const WindowedGrid& grid, const std::vector<Complex>& r, bool real_signal, double& bin) {
  std::size_t m = 1;
  while (m < 2 * grid.n) m <<= 1;
  std::vector<Complex> x(m);
  for (std::size_t i = 0; i < grid.n; ++i) x[i] = grid.weight[i] * r[i];
  fft_in_place(x, [&grid] { check_stop(grid); });
  bin = 2.0 * std::numbers::pi / (static_cast<double>(m) * grid.dt);
  const std::size_t first = real_signal ? 1 : 0, last = real_signal ? m / 2 : m - 1;
  std::size_t best = first;
  for (std::size_t k = first; k <= last; ++k)
    if (std::norm(x[k]) > std::norm(x[best])) best = k;
  const auto signed_bin = best <= m / 2 ? static_cast<double>(best) : static_cast<double>(best) - static_cast<double>(m);
  return signed_bin * bin;
}

}  // namespace

double projection_power(const WindowedGrid& grid, const std::vector<Complex>& r, double omega, bool real_signal) {
  return power_and_slope(grid, r, omega, real_signal).power;
}

double strongest_frequency(const WindowedGrid& grid, const std::vector<Complex>& r, bool real_signal) {
  double bin = 0.0;
  const double coarse = coarse_peak(grid, r, real_signal, bin);
  const double lo = real_signal ? std::max(coarse - bin, 0.25 * bin) : coarse - bin, hi = coarse + bin;
  std::uintmax_t iterations = 200;
  const auto minus_power = [&](double w) { return -power_and_slope(grid, r, w, real_signal).power; };
  const double brent =
      boost::math::tools::brent_find_minima(minus_power, lo, hi, std::numeric_limits<double>::digits / 2, iterations)
          .first;
  // The maximum is where the slope changes sign from + to −: solve for it to full precision.
  const auto slope = [&](double w) { return power_and_slope(grid, r, w, real_signal).slope; };
  const double delta = 1e-4 * bin;
  const double a = std::max(brent - delta, lo), b = std::min(brent + delta, hi);
  if (!(slope(a) > 0.0 && slope(b) < 0.0)) return brent;
  iterations = 100;
  const auto root =
      boost::math::tools::toms748_solve(slope, a, b, boost::math::tools::eps_tolerance<double>(50), iterations);
  return 0.5 * (root.first + root.second);
}

}  // namespace lgi::experiments::frequency
