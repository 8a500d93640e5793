#pragma once
// `lgi simulate --output-dt D` (and lgi.simulate(output_dt=D)): samples at
// the times t0, t0 + D, t0 + 2D, … and t_end, through RunConfig::output_times
// (integrators/core/stepper_loop.hpp). An adaptive scheme with dense output
// interpolates them inside its steps (its steps are those of a run without
// them); one without dense output shortens a step to land on each; a
// fixed-step scheme is observed on its own grid, so D must be a whole
// multiple of its step.
#include <cstdint>
#include <optional>
#include <vector>

#include "integrators/registry/registry.hpp"

namespace lgi::experiments {

/// At most this many output times in one run.
inline constexpr double max_output_times = 1e8;

/// Throws UsageError naming --output-dt when D is not a positive finite
/// number or is given with --save-every N > 1 (the checks without a scene).
void check_output_dt_flag(double output_dt, std::int64_t save_every);

/// Throws UsageError naming --output-dt when D asks for more than
/// max_output_times samples over the run, or (fixed-step schemes) is not a
/// whole multiple of the step cfg.dt to 1e-9 relative.
void check_output_dt(double output_dt, const integrators::RunConfig& cfg, const integrators::SchemeInfo& scheme);

/// The number of times output_grid(t0, t_end, D) holds (after check_output_dt).
std::int64_t output_sample_count(double t0, double t_end, double output_dt);

/// t0 + k D for k = 0, 1, … while below t_end (a last interval that is a
/// whole interval to 1e-10 relative ends at t_end itself), then t_end:
/// sorted, within [t0, t_end], as RunConfig::output_times requires.
std::vector<double> output_grid(double t0, double t_end, double output_dt);

}  // namespace lgi::experiments
