#include "experiments/cli/output_grid.hpp"

#include <cmath>
#include <string>

#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "integrators/core/loop_support.hpp"

namespace lgi::experiments {

void check_output_dt_flag(double output_dt, std::int64_t save_every) {
  if (!(output_dt > 0.0) || !std::isfinite(output_dt)) throw UsageError("--output-dt: must be a positive number");
  if (save_every != 1) throw UsageError("--output-dt: give --output-dt or --save-every, not both");
}

void check_output_dt(double output_dt, const integrators::RunConfig& cfg, const integrators::SchemeInfo& scheme) {
  const double span = cfg.t_end - cfg.t0;
  const double samples = std::floor(span / output_dt) + 2.0;
  if (samples > max_output_times)
    throw UsageError("--output-dt: " + format_general(output_dt, 6) + " asks for " + format_general(samples, 3) +
                     " samples over t_end = " + format_general(cfg.t_end, 6) + "; at most 1e8");
  if (scheme.properties.adaptive) return;
  const double ratio = output_dt / cfg.dt, whole = std::round(ratio);
  if (!(whole >= 1.0) || std::abs(ratio - whole) > 1e-9 * whole)
    throw UsageError("--output-dt: " + format_general(output_dt, 10) + " is not a whole multiple of the step dt = " +
                     format_general(cfg.dt, 10) + " (a fixed-step scheme is observed at its own step times)");
}

std::int64_t output_sample_count(double t0, double t_end, double output_dt) {
  return integrators::fixed_step_count(t_end - t0, output_dt) + 1;
}

std::vector<double> output_grid(double t0, double t_end, double output_dt) {
  const std::int64_t intervals = output_sample_count(t0, t_end, output_dt) - 1;
  std::vector<double> times;
  times.reserve(static_cast<std::size_t>(intervals) + 1);
  for (std::int64_t k = 0; k < intervals; ++k) times.push_back(t0 + static_cast<double>(k) * output_dt);
  times.push_back(t_end);
  return times;
}

}  // namespace lgi::experiments
