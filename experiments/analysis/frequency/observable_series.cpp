// Observables at uniform times (observable_series.hpp).
#include "experiments/analysis/frequency/observable_series.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrators/system/invariants.hpp"
#include "integrators/system/model.hpp"

namespace lgi::experiments::frequency {
namespace {

/// Appends the requested components of each observed state.
class SeriesObserver final : public integrators::Observer {
 public:
  SeriesObserver(const system::SceneInvariants& invariants, const std::vector<int>& which, std::size_t expected)
      : invariants_(invariants), which_(which), series_(which.size()) {
    for (auto& s : series_) s.reserve(expected);
  }
  void observe(std::int64_t, double, const system::State& s) override {
    const lie::Vec3 gamma = s.R.transpose() * lie::Vec3::UnitZ();
    const lie::Vec3 omega = invariants_.omega(s);
    for (std::size_t k = 0; k < which_.size(); ++k) {
      const int q = which_[k];
      const lie::Vec3& v = q < 3 ? s.Pi : q < 6 ? gamma : omega;
      series_[k].push_back(v[q % 3]);
    }
  }
  std::vector<std::vector<double>>&& take() { return std::move(series_); }

 private:
  const system::SceneInvariants& invariants_;
  const std::vector<int>& which_;
  std::vector<std::vector<double>> series_;
};

std::vector<int> indices_of(const std::vector<std::string>& names) {
  const auto& all = observable_names();
  std::vector<int> which;
  for (const auto& n : names) {
    const auto it = std::find(all.begin(), all.end(), n);
    if (it == all.end())
      throw std::invalid_argument("unknown observable '" + n +
                                  "' (angular_momentum_1..3, gamma_1..3, angular_velocity_1..3; Cardan scenes: "
                                  "cardan_angle_1..3, cardan_momentum_1..3, cos_cardan_angle_1..3, sin_cardan_angle_1..3)");
    which.push_back(static_cast<int>(it - all.begin()));
  }
  return which;
}

}  // namespace

const std::vector<std::string>& observable_names() {
  static const std::vector<std::string> names = {
      "angular_momentum_1", "angular_momentum_2", "angular_momentum_3", "gamma_1",           "gamma_2",
      "gamma_3",            "angular_velocity_1", "angular_velocity_2", "angular_velocity_3"};
  return names;
}

std::optional<std::pair<std::string, std::string>> complex_pair(const std::string& observable) {
  const std::size_t plus = observable.find("+i");
  if (plus == std::string::npos) return std::nullopt;
  return std::make_pair(observable.substr(0, plus), observable.substr(plus + 2));
}

std::vector<std::string> components_of(const std::vector<std::string>& observables) {
  std::vector<std::string> out;
  const auto& cardan = cardan_observable_names();
  const auto add = [&](const std::string& name) {
    if (std::find(cardan.begin(), cardan.end(), name) == cardan.end()) indices_of({name});  // throws on an unknown name
    if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  };
  for (const auto& o : observables) {
    if (const auto pair = complex_pair(o)) {
      add(pair->first);
      add(pair->second);
    } else {
      add(o);
    }
  }
  return out;
}

SampledRun sample_observables(const system::Scene& scene, const integrators::SchemeInfo& scheme,
                              const SamplingSettings& settings, const std::vector<std::string>& names,
                              const std::atomic<bool>* stop) {
  const std::vector<int> which = indices_of(names);
  const double D = settings.output_dt;
  if (!scheme.properties.adaptive) {
    const double ratio = D / settings.dt;
    if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio || std::round(ratio) < 1.0)
      throw std::invalid_argument("the output step is not a whole multiple of the scheme's step " +
                                  std::to_string(settings.dt));
  }
  const double t0 = 0.0;
  const auto intervals = static_cast<std::size_t>(std::floor((settings.t_end - t0) / D * (1.0 + 1e-12)));
  if (intervals < 15 || intervals > 100'000'000)
    throw std::invalid_argument("the run holds " + std::to_string(intervals + 1) +
                                " output times; frequency analysis needs 16 to 1e8");
  std::vector<double> times(intervals + 1);
  for (std::size_t k = 0; k <= intervals; ++k) times[k] = t0 + static_cast<double>(k) * D;
  const system::AnyModel model = system::make_model(scene);
  if (const std::string why = integrators::unsupported_reason(scheme, model); !why.empty())
    throw std::invalid_argument("scheme " + scheme.name + " " + why);
  integrators::RunConfig cfg;
  cfg.t0 = t0;
  cfg.t_end = times.back();
  cfg.dt = settings.dt;
  cfg.tol = scheme.properties.adaptive ? settings.tol : 0.0;
  cfg.output_times = &times;
  cfg.stop = stop;
  const system::SceneInvariants invariants(scene, model);
  SeriesObserver observer(invariants, which, times.size());
  system::State x = scene.initial;
  SampledRun run;
  run.t0 = t0;
  run.output_dt = D;
  run.stats = scheme.run(model, x, cfg, observer);
  run.series = observer.take();
  if (run.stats.ok && !run.series.empty() && run.series[0].size() != times.size()) {
    run.stats.ok = false;
    run.stats.status = "observed " + std::to_string(run.series[0].size()) + " of " + std::to_string(times.size()) +
                       " output times";
  }
  return run;
}

}  // namespace lgi::experiments::frequency
