#pragma once
// The spectral rigidity Δ₃(L) of Dyson and Mehta (F. J. Dyson and M. L.
// Mehta, J. Math. Phys. 4 (1963) 701): the least-squares deviation of the
// unfolded staircase N(x) from a straight line over a window of length L,
//   Δ₃(x, L) = min_{A,B} (1/L) ∫_x^{x+L} [N(ξ) − Aξ − B]² dξ,
// averaged over the window starts x (O. Bohigas and M.-J. Giannoni, Lecture
// Notes in Physics 209 (1984) 1; Haake, Quantum Signatures of Chaos, 4th ed.
// 2018, ch. 4; docs/spectral_statistics.md §4). L/15 for Poisson levels,
// ~ (1/π²) ln L for the GOE, 1/12 − 1/(60 L²) at integer L for a picket fence.
#include <span>

#include "experiments/analysis/spectral/level_windows.hpp"

namespace lgi::experiments::spectral {

/// Δ₃(x, L) of one window in closed form (no quadrature): with the n levels
/// inside at ε_k = x_k − (x + L/2), k = 1 … n ascending,
///   Δ₃ = n²/16 − (Σε_k)²/L² + 3n Σε_k²/(2L²) − 3(Σε_k²)²/L⁴ + Σ(n − 2k + 1) ε_k / L
/// (Bohigas & Giannoni 1984; derived in docs/spectral_statistics.md §4).
double delta3_window(std::span<const double> unfolded, double start, double length);

/// Δ₃(L) averaged over all starts in [x_0, x_{n−1} − L]: Δ₃(x, L) is a
/// polynomial of degree 4 in x on each segment with fixed levels, integrated
/// exactly by 3-point Gauss–Legendre. Standard error from the disjoint
/// windows. Sorted unfolded levels.
WindowStatistic spectral_rigidity(std::span<const double> unfolded, double length);

}  // namespace lgi::experiments::spectral
