#pragma once
// An in-place radix-2 fast Fourier transform, for the coarse peak search of
// NAFF (naff.hpp): X_k = Σ_j x_j e^{−2πi jk/n}, n a power of two.
#include <complex>
#include <vector>

namespace lgi::experiments::frequency {

/// Transforms x in place; x.size() must be a power of two (≥ 1).
void fft_in_place(std::vector<std::complex<double>>& x);

}  // namespace lgi::experiments::frequency
