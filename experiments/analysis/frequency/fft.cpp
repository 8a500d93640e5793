// Radix-2 decimation-in-time FFT (Cooley & Tukey 1965), iterative with a
// bit-reversal permutation; twiddles computed exactly per stage (no recurrence
// over the stage, so no drift of the roots of unity).
#include "experiments/analysis/frequency/fft.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace lgi::experiments::frequency {

void fft_in_place(std::vector<std::complex<double>>& x, const std::function<void()>& stop_check) {
  const std::size_t n = x.size();
  if (n == 0 || (n & (n - 1)) != 0) throw std::invalid_argument("fft_in_place: the size is not a power of two");
  constexpr std::size_t check_every = std::size_t{1} << 16;
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    if (stop_check && i % check_every == 0) stop_check();
    std::size_t bit = n >> 1;
    for (; (j & bit) != 0; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(x[i], x[j]);
  }
  std::vector<std::complex<double>> roots;
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const std::size_t half = len / 2;
    roots.resize(half);
    for (std::size_t k = 0; k < half; ++k)
      roots[k] = std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(len));
    std::size_t since_check = 0;
    for (std::size_t start = 0; start < n; start += len)
      for (std::size_t k0 = 0; k0 < half; k0 += check_every) {
        const std::size_t k1 = std::min(half, k0 + check_every);
        if (stop_check && (since_check += k1 - k0) >= check_every) {
          since_check = 0;
          stop_check();
        }
        for (std::size_t k = k0; k < k1; ++k) {
          const std::complex<double> a = x[start + k], b = x[start + k + half] * roots[k];
          x[start + k] = a + b;
          x[start + k + half] = a - b;
        }
      }
  }
}

}  // namespace lgi::experiments::frequency
