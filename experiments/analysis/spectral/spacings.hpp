#pragma once
// Nearest-neighbour spacings of an unfolded spectrum and their histogram
// (Haake, Quantum Signatures of Chaos, 4th ed. 2018, ch. 4;
// docs/spectral_statistics.md §2).
#include <cstddef>
#include <span>
#include <vector>

namespace lgi::experiments::spectral {

/// s_i = (x_{i+1} − x_i) / mean spacing, i = 0 … n − 2, on sorted unfolded
/// levels: normalised to mean 1 exactly, so that the Brody and the reference
/// densities (all of mean 1) apply whatever small drift the unfolding left.
/// Throws InputError (message starting with "spectral statistics") if fewer
/// than 3 levels, unsorted or non-finite levels, or all spacings zero.
std::vector<double> nearest_spacings(std::span<const double> unfolded);

/// The density of the spacings in bins [k w, (k + 1) w), k = 0 … ⌈s_max/w⌉ − 1:
/// density_k = count_k / (n w), with its counting error √count_k / (n w),
/// n all the spacings (so the density integrates to the fraction below s_max;
/// `above` counts the rest).
struct SpacingHistogram {
  double bin_width = 0.0;
  std::vector<double> centres, density, density_error;
  std::vector<std::size_t> counts;
  std::size_t above = 0;
};

/// Default bins: width 0.1 up to 4 (a GOE spacing exceeds 4 with probability
/// e^{−4π} ≈ 3.5e-6 under the Wigner surmise, a Poisson one with e^{−4} ≈ 0.018).
inline constexpr double kDefaultBinWidth = 0.1;
inline constexpr double kDefaultSpacingMax = 4.0;

/// Throws InputError unless 0 < bin_width <= s_max, both finite.
SpacingHistogram spacing_histogram(std::span<const double> spacings, double bin_width = kDefaultBinWidth,
                                   double s_max = kDefaultSpacingMax);

}  // namespace lgi::experiments::spectral
