#pragma once
// The number variance Σ²(L): the variance of the number n(x, L) of unfolded
// levels in a window [x, x + L] over the window starts x (Haake, Quantum
// Signatures of Chaos, 4th ed. 2018, ch. 4; M. L. Mehta, Random Matrices,
// 3rd ed. 2004, ch. 16; docs/spectral_statistics.md §4). Σ²(L) = L for
// Poisson levels, ~ (2/π²) ln L for the GOE, 0 at integer L for a picket fence.
#include <span>

#include "experiments/analysis/spectral/level_windows.hpp"

namespace lgi::experiments::spectral {

/// Σ²(L) = ⟨n²⟩ − ⟨n⟩² with ⟨·⟩ the exact average over all starts in
/// [x_0, x_{n−1} − L] (n is piecewise constant in x); the spread is taken
/// about the measured ⟨n⟩, not about L, so a small drift of the unfolding's
/// density does not add (⟨n⟩ − L)². Standard error: from the values
/// (n_k − ⟨n⟩)² of the disjoint windows. Sorted unfolded levels.
WindowStatistic number_variance(std::span<const double> unfolded, double length);

}  // namespace lgi::experiments::spectral
