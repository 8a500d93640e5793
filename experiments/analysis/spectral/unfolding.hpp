#pragma once
// Unfolding a spectrum: the levels E_i mapped through a smooth counting
// function, x_i = N_smooth(E_i), so that the unfolded levels have mean
// spacing 1 everywhere and fluctuation statistics of different parts of a
// spectrum (and of different spectra) can be compared (Haake, Quantum
// Signatures of Chaos, 4th ed. 2018, ch. 4; docs/spectral_statistics.md §1).
// N_smooth should be Weyl's law, the phase-space volume below E over
// (2πħ)^d, whenever the caller has it; the polynomial fit of the staircase
// here is the fallback for when it does not.
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace lgi::experiments::spectral {

/// N_smooth(E) as a polynomial in t = (E − centre)/half_width (scaled so that
/// the fitted levels span t in [−1, 1], which keeps the fit well conditioned).
struct StaircaseFit {
  std::vector<double> coefficients;  // c_0 … c_degree of Σ c_k t^k
  double centre = 0.0, half_width = 1.0;
  double operator()(double energy) const;
};

/// The default degree of the polynomial fit: 5 follows the smooth part of a
/// semicircle or of a Weyl law with its boundary terms over a stretch of
/// spectrum without following its fluctuations, which extend over a few levels.
inline constexpr int kDefaultFitDegree = 5;

/// The least-squares polynomial of `degree` through the staircase's midpoints
/// (E_i, i + 1/2), i = 0 … n − 1, on sorted finite levels. The fit must stay
/// increasing over the levels (else unfolding would reorder them): a fit that
/// does not throws InputError naming the degree. Needs n > degree + 1 levels.
StaircaseFit fit_staircase(std::span<const double> levels, int degree = kDefaultFitDegree);

/// x_i = n_smooth(E_i) for sorted finite levels; throws InputError (its
/// message starts with `what`) if the levels are not sorted or finite, or if
/// the unfolded levels are not increasing (a counting function that is not).
std::vector<double> unfold(std::span<const double> levels, const std::function<double(double)>& n_smooth,
                           const std::string& what = "spectral statistics");

/// InputError unless the levels are finite and sorted (non-decreasing).
void check_levels(std::span<const double> levels, const std::string& what);

}  // namespace lgi::experiments::spectral
