#include "experiments/cli/step_settings.hpp"

#include <cmath>
#include <string>

#include "experiments/errors/exit_status.hpp"
#include "integrators/core/loop_support.hpp"

namespace lgi::experiments {
namespace {

bool positive_finite(double x) { return x > 0.0 && std::isfinite(x); }

void check_t_end_flag(const std::optional<double>& flag, bool allow_zero) {
  if (flag && (!std::isfinite(*flag) || *flag < 0.0 || (!allow_zero && *flag == 0.0)))
    throw UsageError(std::string("--t-end: must be a finite number ") + (allow_zero ? ">= 0" : "> 0"));
}

}  // namespace

void check_step_flags(const StepFlags& flags, bool allow_zero_t_end) {
  check_t_end_flag(flags.t_end, allow_zero_t_end);
  if (flags.dt && !positive_finite(*flags.dt)) throw UsageError("--dt: must be a finite number > 0");
  if (flags.tol && !positive_finite(*flags.tol)) throw UsageError("--tol: must be a finite number > 0");
  // A relative tolerance of 1 or more asks for no accuracy at all (the controller
  // then takes any step the stability allows): refused rather than run.
  if (flags.tol && *flags.tol >= 1.0) throw UsageError("--tol: must be below 1 (a relative tolerance)");
}

double resolve_t_end(const std::optional<double>& flag, const system::Scene& scene, bool allow_zero) {
  if (flag) {
    check_t_end_flag(flag, allow_zero);
    return *flag;
  }
  if (!scene.t_end) throw UsageError("--t-end: needed, since " + scene.file + " has no [run] t_end");
  if (!allow_zero && !(*scene.t_end > 0.0))
    throw UsageError("--t-end: needed, since the [run] t_end of " + scene.file + " is not > 0");
  return *scene.t_end;
}

integrators::RunConfig resolve_run_config(const StepFlags& flags, const system::Scene& scene,
                                          const integrators::SchemeInfo& scheme, bool allow_zero_t_end) {
  check_step_flags(flags, allow_zero_t_end);
  integrators::RunConfig cfg;
  cfg.t_end = resolve_t_end(flags.t_end, scene, allow_zero_t_end);
  const std::string name = "scheme '" + scheme.name + "'";
  if (scheme.properties.adaptive) {
    if (!flags.tol && !scene.tol)
      throw UsageError("--tol: " + name + " is adaptive and needs a tolerance: give --tol or [run] tol in " +
                       scene.file);
    cfg.tol = flags.tol ? *flags.tol : *scene.tol;
    cfg.dt = flags.dt.value_or(0.0);  // the first trial step; 0 lets the scheme choose
    return cfg;
  }
  if (flags.tol)
    throw UsageError("--tol: " + name + " is fixed-step and takes no tolerance; " +
                     (flags.dt ? std::string("drop --tol (the step is --dt)")
                               : "give its step with --dt (or [run] dt in " + scene.file + ") instead"));
  if (!flags.dt && !scene.dt)
    throw UsageError("--dt: " + name + " needs a step: give --dt or [run] dt in " + scene.file);
  cfg.dt = flags.dt ? *flags.dt : *scene.dt;
  if (const std::string why = integrators::fixed_step_grid_problem(cfg.t0, cfg.t_end, cfg.dt); !why.empty())
    throw UsageError(std::string(flags.dt ? "--dt: " : "--dt ([run] dt of " + scene.file + "): ") + why);
  return cfg;
}

std::vector<double> default_step_list(const std::vector<double>& flag, const std::optional<double>& scene_dt) {
  if (!flag.empty() || !scene_dt) return flag;
  return {*scene_dt, *scene_dt / 2.0, *scene_dt / 4.0, *scene_dt / 8.0};
}

std::vector<double> default_tolerance_list(const std::vector<double>& flag, const std::optional<double>& scene_tol) {
  if (!flag.empty() || !scene_tol) return flag;
  return {*scene_tol, *scene_tol * 1e-1, *scene_tol * 1e-2, *scene_tol * 1e-3};
}

}  // namespace lgi::experiments
