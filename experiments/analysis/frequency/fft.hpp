#pragma once
// An in-place radix-2 fast Fourier transform, for the coarse peak search of
// NAFF (naff.hpp): X_k = Σ_j x_j e^{−2πi jk/n}, n a power of two.
#include <complex>
#include <functional>
#include <vector>

namespace lgi::experiments::frequency {

/// Transforms x in place; x.size() must be a power of two (≥ 1). `stop_check`, if given, is
/// called every 2^16 butterflies or swaps (it may throw to abandon the transform).
void fft_in_place(std::vector<std::complex<double>>& x, const std::function<void()>& stop_check = {});

}  // namespace lgi::experiments::frequency
