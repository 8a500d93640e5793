// NAFF per observable (observable_frequencies.hpp).
#include "experiments/analysis/frequency/observable_frequencies.hpp"

#include <algorithm>
#include <complex>
#include <cstdint>
#include <exception>
#include <limits>
#include <type_traits>

namespace lgi::experiments::frequency {
namespace {

const std::vector<double>& series_of(const SampledRun& run, const std::vector<std::string>& components,
                                     const std::string& name) {
  const auto it = std::find(components.begin(), components.end(), name);
  return run.series[static_cast<std::size_t>(it - components.begin())];
}

template <class T>
ObservableFrequencies analysed(const std::string& observable, const std::vector<T>& f, double dt,
                               const NaffOptions& options) {
  ObservableFrequencies r;
  r.observable = observable;
  if constexpr (std::is_same_v<T, double>) r.terms = naff_real(f, dt, options);
  else r.terms = naff_complex(f, dt, options);
  if (r.terms.terms.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    r.diffusion = {nan, nan, nan, nan};
  } else {
    r.diffusion = frequency_diffusion(f, dt, options, r.terms.terms[0].frequency);
  }
  return r;
}

}  // namespace

std::vector<ObservableFrequencies> observable_frequencies(const SampledRun& run,
                                                          const std::vector<std::string>& observables,
                                                          const NaffOptions& options, int threads) {
  const std::vector<std::string> components = components_of(observables);
  std::vector<ObservableFrequencies> out(observables.size());
  std::exception_ptr failure;  // an exception may not leave an OpenMP region
  const auto n = static_cast<std::int64_t>(observables.size());
#pragma omp parallel for num_threads(std::max(1, threads)) schedule(dynamic, 1)
  for (std::int64_t k = 0; k < n; ++k) {
    const std::string& o = observables[static_cast<std::size_t>(k)];
    try {
      if (const auto pair = complex_pair(o)) {
        const std::vector<double>& a = series_of(run, components, pair->first);
        const std::vector<double>& b = series_of(run, components, pair->second);
        std::vector<std::complex<double>> z(a.size());
        for (std::size_t i = 0; i < a.size(); ++i) z[i] = {a[i], b[i]};
        out[static_cast<std::size_t>(k)] = analysed(o, z, run.output_dt, options);
      } else {
        out[static_cast<std::size_t>(k)] = analysed(o, series_of(run, components, o), run.output_dt, options);
      }
    } catch (...) {
#pragma omp critical(lgi_frequencies_failure)
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  return out;
}

}  // namespace lgi::experiments::frequency
