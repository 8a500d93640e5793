// Spectral statistics of a spectrum and per symmetry class (spectral_statistics.hpp).
#include "experiments/analysis/spectral/spectral_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "experiments/analysis/spectral/number_variance.hpp"
#include "experiments/analysis/spectral/spectral_rigidity.hpp"
#include "experiments/errors/input_error.hpp"

namespace lgi::experiments::spectral {

SpectralStatistics spectral_statistics(std::span<const double> unfolded, const StatisticsOptions& options) {
  SpectralStatistics out;
  out.levels = unfolded.size();
  out.spacings = nearest_spacings(unfolded);
  out.histogram = spacing_histogram(out.spacings, options.bin_width, options.s_max);
  out.brody = fit_brody(out.spacings);
  for (double length : options.lengths) {
    out.number_variance.push_back(number_variance(unfolded, length));
    out.rigidity.push_back(spectral_rigidity(unfolded, length));
  }
  return out;
}

std::vector<ClassStatistics> statistics_by_class(std::span<const double> levels, std::span<const int> classes,
                                                 const ClassCounting& n_smooth, const StatisticsOptions& options) {
  if (levels.size() != classes.size())
    throw InputError("spectral statistics: " + std::to_string(levels.size()) + " levels but " +
                     std::to_string(classes.size()) + " class labels");
  std::map<int, std::vector<double>> by_class;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    // Checked before sorting: a NaN breaks std::sort's ordering.
    if (!std::isfinite(levels[i]))
      throw InputError("spectral statistics: level " + std::to_string(i) + " is not a finite number");
    by_class[classes[i]].push_back(levels[i]);
  }
  std::vector<ClassStatistics> out;
  const std::size_t needed =
      n_smooth ? 3 : std::max<std::size_t>(3, static_cast<std::size_t>(std::max(options.fit_degree, 1)) + 2);
  for (auto& [label, energies] : by_class) {
    std::sort(energies.begin(), energies.end());
    ClassStatistics c;
    c.label = label;
    c.statistics.levels = energies.size();
    if (energies.size() < needed) {
      c.too_few = true;
      out.push_back(std::move(c));
      continue;
    }
    const std::string what = "spectral statistics: class " + std::to_string(label);
    std::vector<double> x;
    if (n_smooth) {
      const int l = label;
      x = unfold(energies, [&n_smooth, l](double e) { return n_smooth(l, e); }, what);
    } else {
      StaircaseFit fit;
      try {
        fit = fit_staircase(energies, options.fit_degree);
      } catch (const InputError& e) {
        throw InputError(what + ": " + e.what());
      }
      x = unfold(energies, fit, what);
    }
    c.statistics = spectral_statistics(x, options);
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace lgi::experiments::spectral
