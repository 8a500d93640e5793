// NAFF per observable (observable_frequencies.hpp).
#include "experiments/analysis/frequency/observable_frequencies.hpp"

#include <limits>

namespace lgi::experiments::frequency {

std::vector<ObservableFrequencies> observable_frequencies(const SampledRun& run, const std::vector<std::string>& names,
                                                          const NaffOptions& options) {
  std::vector<ObservableFrequencies> out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    ObservableFrequencies r;
    r.observable = names[k];
    r.terms = naff_real(run.series[k], run.output_dt, options);
    if (r.terms.terms.empty()) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      r.diffusion = {nan, nan, nan, nan};
    } else {
      r.diffusion = frequency_diffusion(run.series[k], run.output_dt, options, r.terms.terms[0].frequency);
    }
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace lgi::experiments::frequency
