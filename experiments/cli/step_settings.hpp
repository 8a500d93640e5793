#pragma once
// One rule for the run settings of every subcommand: the command line, then
// the scene's [run] table, then a documented default. A value that is still
// missing is a usage error naming the flag (and the scene key that would do).
#include <optional>
#include <vector>

#include "integrators/registry/registry.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// The flags as given (unset when absent).
struct StepFlags {
  std::optional<double> dt, tol, t_end;
};

/// Throws UsageError naming the flag when a given --t-end, --dt or --tol is
/// out of range (t_end finite and > 0, or >= 0 with allow_zero_t_end; dt and
/// tol finite and > 0). Needs no scene: the check right after the parse.
void check_step_flags(const StepFlags& flags, bool allow_zero_t_end);

/// The final time: --t-end, else [run] t_end; throws UsageError if neither.
/// `allow_zero`: t_end = 0 is a valid run (simulate) or not (studies).
double resolve_t_end(const std::optional<double>& flag, const system::Scene& scene, bool allow_zero);

/// t_end, dt (fixed step, or the first trial step of an adaptive scheme; 0:
/// automatic) and tol for one scheme, checked against the scheme's kind.
integrators::RunConfig resolve_run_config(const StepFlags& flags, const system::Scene& scene,
                                          const integrators::SchemeInfo& scheme, bool allow_zero_t_end);

/// Lists for work-precision: --dt (else [run] dt times 1, 1/2, 1/4, 1/8) and
/// --tol (else [run] tol times 1, 1e-1, 1e-2, 1e-3); empty if neither is given.
std::vector<double> default_step_list(const std::vector<double>& flag, const std::optional<double>& scene_dt);
std::vector<double> default_tolerance_list(const std::vector<double>& flag, const std::optional<double>& scene_tol);

}  // namespace lgi::experiments
