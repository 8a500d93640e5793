#pragma once
// The fluctuation statistics of a spectrum in one call: spacings, their
// histogram, the Brody parameter, Σ²(L) and Δ₃(L) of unfolded levels; and
// the same per symmetry class (docs/spectral_statistics.md §7). Levels of
// different symmetry classes are independent of one another, and a
// superposition of independent spectra looks more Poissonian than each of
// them (Haake, Quantum Signatures of Chaos, 4th ed. 2018, ch. 4; for m
// classes of fractions f_i, Σ²(L) = Σ_i Σ²_i(f_i L)): split first.
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "experiments/analysis/spectral/brody_fit.hpp"
#include "experiments/analysis/spectral/level_windows.hpp"
#include "experiments/analysis/spectral/spacings.hpp"
#include "experiments/analysis/spectral/unfolding.hpp"

namespace lgi::experiments::spectral {

struct StatisticsOptions {
  /// The window lengths L of Σ²(L) and Δ₃(L) (in mean spacings).
  std::vector<double> lengths{0.5, 1, 1.5, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20};
  double bin_width = kDefaultBinWidth, s_max = kDefaultSpacingMax;
  /// The degree of the staircase fit when no counting function is given.
  int fit_degree = kDefaultFitDegree;
};

struct SpectralStatistics {
  std::size_t levels = 0;
  std::vector<double> spacings;  // mean 1
  SpacingHistogram histogram;
  BrodyFit brody;
  std::vector<WindowStatistic> number_variance, rigidity;  // one per length
};

/// The statistics of sorted unfolded levels (InputError as nearest_spacings).
SpectralStatistics spectral_statistics(std::span<const double> unfolded, const StatisticsOptions& options = {});

/// One symmetry class: its label and statistics. A class with fewer than
/// max(3, fit_degree + 2) levels (when fitted) or 3 (when a counting function
/// is given) is kept with `levels` set and nothing computed (too_few).
struct ClassStatistics {
  int label = 0;
  bool too_few = false;
  SpectralStatistics statistics;
};

/// The counting function of one class: N_smooth(label, E).
using ClassCounting = std::function<double(int, double)>;

/// Splits levels (any order) by their class labels (same length; InputError
/// otherwise), sorts each class, unfolds it by n_smooth(label, ·) or, when
/// n_smooth is empty, by its own staircase fit of options.fit_degree, and
/// computes its statistics. Classes in increasing label order.
std::vector<ClassStatistics> statistics_by_class(std::span<const double> levels, std::span<const int> classes,
                                                 const ClassCounting& n_smooth = {},
                                                 const StatisticsOptions& options = {});

}  // namespace lgi::experiments::spectral
