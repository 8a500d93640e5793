// The diffusion index (frequency_diffusion.hpp).
#include "experiments/analysis/frequency/frequency_diffusion.hpp"

#include <cmath>
#include <limits>

namespace lgi::experiments::frequency {
namespace {

/// The term of the half run nearest the whole run's leading frequency: a line
/// whose amplitude is close to another's may swap places between the halves.
double nearest(const NaffResult& r, double leading) {
  double best = std::numeric_limits<double>::quiet_NaN();
  for (const NaffTerm& t : r.terms)
    if (std::isnan(best) || std::abs(t.frequency - leading) < std::abs(best - leading)) best = t.frequency;
  return best;
}

NaffResult analyse(const std::vector<double>& f, double dt, const NaffOptions& o) { return naff_real(f, dt, o); }
NaffResult analyse(const std::vector<std::complex<double>>& f, double dt, const NaffOptions& o) {
  return naff_complex(f, dt, o);
}

template <class T>
FrequencyDiffusion halves(const std::vector<T>& f, double dt, const NaffOptions& options, double leading) {
  const std::size_t half = f.size() / 2;
  const auto middle = f.begin() + static_cast<std::ptrdiff_t>(half);
  const std::vector<T> first(f.begin(), middle + 1), second(middle, f.end());
  FrequencyDiffusion d;
  d.first_half = nearest(analyse(first, dt, options), leading);
  d.second_half = nearest(analyse(second, dt, options), leading);
  d.relative_change = std::abs(d.second_half - d.first_half) / std::abs(d.first_half);
  d.log10_relative_change = std::log10(d.relative_change);
  return d;
}

}  // namespace

FrequencyDiffusion frequency_diffusion(const std::vector<double>& f, double dt, const NaffOptions& options,
                                       double leading) {
  return halves(f, dt, options, leading);
}

FrequencyDiffusion frequency_diffusion(const std::vector<std::complex<double>>& f, double dt,
                                       const NaffOptions& options, double leading) {
  return halves(f, dt, options, leading);
}

}  // namespace lgi::experiments::frequency
