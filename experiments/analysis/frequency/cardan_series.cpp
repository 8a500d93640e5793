// Cardan observables at uniform times (cardan_series.hpp).
#include "experiments/analysis/frequency/cardan_series.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrators/core/run_config.hpp"

namespace lgi::experiments::frequency {
namespace {

/// Appends the requested components of each sampled state: q, p, cos q, sin q (name index / 3).
class CardanSeriesObserver final : public integrators::TorusObserver {
 public:
  CardanSeriesObserver(const std::vector<int>& which, std::size_t expected) : which_(which), series_(which.size()) {
    for (auto& s : series_) s.reserve(expected);
  }
  void observe(std::int64_t, double, const system::TorusState& x) override {
    for (std::size_t k = 0; k < which_.size(); ++k) {
      const int kind = which_[k] / 3, i = which_[k] % 3;
      const double v = kind == 0 ? x.q[i] : kind == 1 ? x.p[i] : kind == 2 ? std::cos(x.q[i]) : std::sin(x.q[i]);
      series_[k].push_back(v);
    }
  }
  std::vector<std::vector<double>>&& take() { return std::move(series_); }

 private:
  const std::vector<int>& which_;
  std::vector<std::vector<double>> series_;
};

}  // namespace

const std::vector<std::string>& cardan_observable_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const char* stem : {"cardan_angle_", "cardan_momentum_", "cos_cardan_angle_", "sin_cardan_angle_"})
      for (int i = 1; i <= 3; ++i) n.push_back(stem + std::to_string(i));
    return n;
  }();
  return names;
}

SampledRun sample_cardan_observables(const system::CardanTop& top, const integrators::SchemeInfo& scheme,
                                     const SamplingSettings& settings, const system::TorusState& x0,
                                     const std::vector<std::string>& names, const std::atomic<bool>* stop) {
  const auto& all = cardan_observable_names();
  std::vector<int> which;
  for (const auto& n : names) {
    const auto it = std::find(all.begin(), all.end(), n);
    if (it == all.end()) throw std::invalid_argument("unknown Cardan observable '" + n + "'");
    which.push_back(static_cast<int>(it - all.begin()));
  }
  if (scheme.properties.adaptive)
    throw std::invalid_argument("the T^3 loop samples fixed steps only; " + scheme.name + " is adaptive");
  const double D = settings.output_dt, ratio = D / settings.dt;
  const double every = std::round(ratio);
  if (std::abs(ratio - every) > 1e-9 * ratio || every < 1.0)
    throw std::invalid_argument("the output step is not a whole multiple of the scheme's step " +
                                std::to_string(settings.dt));
  const auto intervals = static_cast<std::size_t>(std::floor(settings.t_end / D * (1.0 + 1e-12)));
  if (intervals < 15 || intervals > 100'000'000)
    throw std::invalid_argument("the run holds " + std::to_string(intervals + 1) +
                                " output times; frequency analysis needs 16 to 1e8");
  integrators::TorusRunConfig cfg;
  cfg.t0 = 0.0;
  cfg.dt = D / every;  // so that the grid lands on every multiple of D
  cfg.t_end = static_cast<double>(intervals) * D;
  cfg.save_every = static_cast<std::int64_t>(every);
  cfg.stop = stop;
  CardanSeriesObserver observer(which, intervals + 1);
  system::TorusState x = x0;
  SampledRun run;
  run.output_dt = D;
  run.stats = scheme.run_cardan(top, x, cfg, observer);
  run.series = observer.take();
  if (run.stats.ok && !run.series.empty() && run.series[0].size() != intervals + 1) {
    run.stats.ok = false;
    run.stats.status = "observed " + std::to_string(run.series[0].size()) + " of " + std::to_string(intervals + 1) +
                       " output times";
  }
  return run;
}

}  // namespace lgi::experiments::frequency
