// Laskar's window χ_p (hann_window.hpp).
#include "experiments/analysis/frequency/hann_window.hpp"

#include <cmath>
#include <numbers>

namespace lgi::experiments::frequency {

std::vector<double> hann_window(std::size_t n, int p) {
  // 2^p (p!)² / (2p)! = Π_{k=1..p} 2k / (p + k): the normalisation of the mean to 1.
  double norm = 1.0;
  for (int k = 1; k <= p; ++k) norm *= 2.0 * k / (p + k);
  std::vector<double> w(n);
  const double last = static_cast<double>(n - 1);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = -1.0 + 2.0 * static_cast<double>(i) / last;
    w[i] = norm * std::pow(1.0 + std::cos(std::numbers::pi * x), p);
  }
  return w;
}

}  // namespace lgi::experiments::frequency
