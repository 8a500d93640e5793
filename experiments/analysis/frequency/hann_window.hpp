#pragma once
// Laskar's window of order p for frequency analysis (docs/frequency_analysis.md §1;
// Laskar, Physica D 67 (1993) 257): χ_p(x) = 2^p (p!)² / (2p)! (1 + cos πx)^p on
// [−1, 1], whose mean over [−1, 1] is 1. The run [t0, t0 + T] is mapped onto [−1, 1].
#include <cstddef>
#include <vector>

namespace lgi::experiments::frequency {

/// χ_p at n ≥ 2 uniform samples x_i = −1 + 2i/(n − 1); p ≥ 0 (p = 0: the flat window).
std::vector<double> hann_window(std::size_t n, int p);

}  // namespace lgi::experiments::frequency
