// lgi.frequencies(): the records of `lgi frequencies` (experiments/FREQUENCIES.md,
// docs/frequency_analysis.md) for a scene: the observables sampled through the
// one loop (analysis/frequency/observable_series.hpp), then NAFF and the
// diffusion index (observable_frequencies.hpp). Bad arguments raise
// ValueError (the analysis's std::invalid_argument).
#include <omp.h>
#include <pybind11/stl.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "experiments/analysis/frequency/observable_frequencies.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

namespace fq = experiments::frequency;

double positive(std::optional<double> v, double fallback, const char* name) {
  const double x = v.value_or(fallback);
  if (!(x > 0.0) || !std::isfinite(x)) throw py::value_error(std::string(name) + ": missing or not a positive number");
  return x;
}

py::dict terms_table(const std::vector<fq::ObservableFrequencies>& records) {
  py::list observable;
  std::vector<std::int64_t> term;
  std::vector<double> frequency, amplitude, phase, period;
  for (const auto& r : records)
    for (std::size_t k = 0; k < r.terms.terms.size(); ++k) {
      const fq::NaffTerm& t = r.terms.terms[k];
      observable.append(r.observable);
      term.push_back(static_cast<std::int64_t>(k));
      frequency.push_back(t.frequency), amplitude.push_back(t.amplitude), phase.push_back(t.phase);
      period.push_back(2.0 * std::numbers::pi / std::abs(t.frequency));
    }
  const auto n = static_cast<py::ssize_t>(term.size());
  py::dict d;
  d["observable"] = observable;
  d["term"] = to_numpy(std::move(term), {n});
  d["frequency"] = to_numpy(std::move(frequency), {n});
  d["amplitude"] = to_numpy(std::move(amplitude), {n});
  d["phase"] = to_numpy(std::move(phase), {n});
  d["period"] = to_numpy(std::move(period), {n});
  return d;
}

py::dict diffusion_table(const std::vector<fq::ObservableFrequencies>& records) {
  py::list observable;
  std::vector<double> leading, first, second, change, log_change, mean;
  for (const auto& r : records) {
    observable.append(r.observable);
    leading.push_back(r.terms.terms.empty() ? std::nan("") : r.terms.terms[0].frequency);
    first.push_back(r.diffusion.first_half), second.push_back(r.diffusion.second_half);
    change.push_back(r.diffusion.relative_change), log_change.push_back(r.diffusion.log10_relative_change);
    mean.push_back(r.terms.mean.real());
  }
  const auto n = static_cast<py::ssize_t>(records.size());
  py::dict d;
  d["observable"] = observable;
  d["frequency"] = to_numpy(std::move(leading), {n});
  d["frequency_first_half"] = to_numpy(std::move(first), {n});
  d["frequency_second_half"] = to_numpy(std::move(second), {n});
  d["relative_change"] = to_numpy(std::move(change), {n});
  d["log10_relative_change"] = to_numpy(std::move(log_change), {n});
  d["mean"] = to_numpy(std::move(mean), {n});
  return d;
}

py::dict frequencies(const py::object& scene_arg, double t_end, const std::optional<std::vector<std::string>>& names,
                     int terms, int window_order, const std::string& scheme_name, std::optional<double> dt,
                     std::optional<double> output_dt, std::optional<double> tol) {
  const std::shared_ptr<const system::Scene> scene = scene_argument(scene_arg);
  if (scene->suspension) throw py::value_error("frequencies: " + scene->file + " is a Cardan top; SO(3) scenes only");
  const integrators::SchemeInfo& scheme = scheme_argument(scheme_name);
  fq::SamplingSettings s;
  s.t_end = positive(t_end, 0.0, "t_end");
  s.dt = positive(dt, scene->dt.value_or(0.0), "dt");
  s.output_dt = positive(output_dt, s.dt, "output_dt");
  s.tol = positive(tol, scene->tol.value_or(1e-10), "tol");
  const std::vector<std::string> observables = names ? *names : fq::observable_names();
  const std::vector<std::string> components = fq::components_of(observables);
  fq::SampledRun run;
  std::vector<fq::ObservableFrequencies> records;
  {
    const py::gil_scoped_release release;
    run = fq::sample_observables(*scene, scheme, s, components, nullptr);
    if (run.stats.ok) records = fq::observable_frequencies(run, observables, {terms, window_order}, omp_get_max_threads());
  }
  if (!run.stats.ok) throw std::runtime_error(scheme.name + " on " + scene->file + ": " + run.stats.status);
  py::dict d;
  d["frequencies"] = terms_table(records);
  d["diffusion"] = diffusion_table(records);
  d["samples"] = run.series.empty() ? 0 : run.series[0].size();
  d["output_dt"] = run.output_dt;
  return d;
}

}  // namespace

void bind_frequencies(py::module_& m) {
  m.def("frequencies", &frequencies, py::arg("scene"), py::arg("t_end"), py::arg("observables") = py::none(),
        py::arg("terms") = 5, py::arg("window_order") = 1, py::arg("scheme") = "split-symmetric@kahan-li8",
        py::arg("dt") = py::none(), py::arg("output_dt") = py::none(), py::arg("tol") = py::none(),
        "NAFF frequencies of observables along the scene's trajectory and their diffusion index: the tables of "
        "`lgi frequencies` (experiments/FREQUENCIES.md) as {'frequencies': {...}, 'diffusion': {...}}.");
}

}  // namespace lgi::python
