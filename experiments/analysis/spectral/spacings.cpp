// Nearest-neighbour spacings and their histogram (spacings.hpp).
#include "experiments/analysis/spectral/spacings.hpp"

#include <cmath>
#include <string>

#include "experiments/analysis/spectral/unfolding.hpp"
#include "experiments/errors/input_error.hpp"

namespace lgi::experiments::spectral {

std::vector<double> nearest_spacings(std::span<const double> unfolded) {
  const std::string what = "spectral statistics";
  check_levels(unfolded, what);
  if (unfolded.size() < 3)
    throw InputError(what + ": " + std::to_string(unfolded.size()) + " levels; at least 3 are needed");
  // The mean spacing is (x_last − x_first)/(n − 1): the sum of the spacings telescopes.
  const double mean = (unfolded.back() - unfolded.front()) / static_cast<double>(unfolded.size() - 1);
  if (!(mean > 0)) throw InputError(what + ": all levels are equal");
  std::vector<double> s(unfolded.size() - 1);
  for (std::size_t i = 0; i + 1 < unfolded.size(); ++i) s[i] = (unfolded[i + 1] - unfolded[i]) / mean;
  return s;
}

SpacingHistogram spacing_histogram(std::span<const double> spacings, double bin_width, double s_max) {
  if (!(bin_width > 0) || !(s_max >= bin_width) || !std::isfinite(s_max))
    throw InputError("spectral statistics: the bin width (" + std::to_string(bin_width) +
                     ") must be positive and at most the largest spacing binned (" + std::to_string(s_max) + ")");
  SpacingHistogram h;
  h.bin_width = bin_width;
  const auto bins = static_cast<std::size_t>(std::ceil(s_max / bin_width - 1e-9));
  h.counts.assign(bins, 0);
  for (double s : spacings) {
    const double k = std::floor(s / bin_width);
    if (k >= static_cast<double>(bins)) {
      ++h.above;
    } else {
      ++h.counts[static_cast<std::size_t>(k)];
    }
  }
  const double norm = static_cast<double>(spacings.size()) * bin_width;
  for (std::size_t k = 0; k < bins; ++k) {
    const double c = static_cast<double>(h.counts[k]);
    h.centres.push_back((static_cast<double>(k) + 0.5) * bin_width);
    h.density.push_back(norm > 0 ? c / norm : NAN);
    h.density_error.push_back(norm > 0 ? std::sqrt(c) / norm : NAN);
  }
  return h;
}

}  // namespace lgi::experiments::spectral
