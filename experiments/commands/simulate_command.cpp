// lgi simulate: scene file → model → scheme → stepper loop → observer (HDF5).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "experiments/cli/commands.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/cli/run_parameters.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/step_settings.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/output_timing.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "integrators/registry.hpp"

namespace lgi::experiments {
namespace {

struct SimulateOptions {
  std::string scene;
  std::string scheme;
  std::optional<double> dt;
  std::optional<double> tol;
  std::optional<double> t_end;
  std::int64_t save_every = 1;
  int retry_halving = 0;
  std::string out;
  bool force = false;
  bool quiet = false;
  std::string command_line;
};

/// Validates flags against the scene and the scheme; fills the run config
/// (the command line, then the scene's [run], step_settings.hpp).
integrators::RunConfig run_config(const SimulateOptions& o, const system::Scene& scene,
                                  const integrators::SchemeInfo& scheme) {
  if (o.save_every < 1) throw UsageError("--save-every: must be >= 1");
  integrators::RunConfig cfg = resolve_run_config({o.dt, o.tol, o.t_end}, scene, scheme, /*allow_zero_t_end=*/true);
  cfg.save_every = o.save_every;
  if (o.retry_halving < 0 || o.retry_halving > 30) throw UsageError("--retry-halving: must be between 0 and 30");
  if (o.retry_halving > 0 && scheme.properties.adaptive)
    throw UsageError("--retry-halving: scheme '" + scheme.name + "' is adaptive and controls its own steps");
  cfg.retry_halving = o.retry_halving;
  return cfg;
}

/// About 128 bytes a sample (time, step, quaternion, Pi, Omega, energy,
/// invariants); a file over 100 MB deserves a word before it is written.
void warn_if_large(const integrators::RunConfig& cfg, const system::SceneInvariants& invariants, bool adaptive,
                   bool quiet) {
  if (quiet || adaptive || cfg.dt <= 0.0) return;
  const double samples = static_cast<double>(integrators::fixed_step_count(cfg.t_end - cfg.t0, cfg.dt)) /
                             static_cast<double>(cfg.save_every) + 1.0;
  const double bytes_per_sample = 8.0 * (16.0 + static_cast<double>(invariants.scalar_names().size()));
  const double megabytes = samples * bytes_per_sample / 1e6;
  if (megabytes < 100.0) return;
  std::cerr << "lgi: warning: --save-every " << cfg.save_every << " writes " << format_general(samples, 3)
            << " samples, about " << format_general(megabytes, 3)
            << " MB; give --save-every N to keep every N-th step\n";
}

int simulate(const SimulateOptions& o) {
  const system::Scene scene = read_scene(o.scene);
  const integrators::SchemeInfo* scheme = &scheme_by_name(o.scheme, "--scheme");
  const integrators::RunConfig cfg = run_config(o, scene, *scheme);
  const system::AnyModel model = system::make_model(scene);
  if (const std::string why = integrators::unsupported_reason(*scheme, model); !why.empty())
    throw RunError(why + "; scene " + scene.file + " is not one");

  const system::SceneInvariants invariants(scene, model);
  const ResultAttributes run = run_parameters(scene, *scheme, cfg, o.command_line);
  Provenance prov{run.text, run.number, run.integer};
  prov.integer_attributes["save_every"] = cfg.save_every;
  if (cfg.retry_halving > 0) prov.integer_attributes["retry_halving"] = cfg.retry_halving;

  warn_if_large(cfg, invariants, scheme->properties.adaptive, o.quiet);
  TrajectoryWriter writer(o.out, o.force, trajectory_layout(invariants, scheme->properties.euler_angle_chart), prov);
  TrajectoryObserver observer(invariants, &writer);
  OutputTimingObserver timed(observer);

  system::State state = scene.initial;
  integrators::RunStats stats;
  {
    const InterruptGuard interrupt_guard;
    integrators::RunConfig c = cfg;
    c.stop = &interrupt_requested;  // every loop (the baselines' too) ends cleanly, with its statistics
    stats = scheme->run(model, state, c, timed);
  }
  // Reported as it always was; the statistics are the loop's own.
  if (stats.interrupted) stats.status = integrators::interrupted_status;

  Diagnostics diag;
  diag.steps = stats.steps;
  diag.rejected_steps = stats.work.rejected_steps;
  diag.rhs_evaluations = stats.work.rhs_evaluations;
  diag.newton_iterations_max = stats.work.newton_iterations_max;
  diag.newton_failures = stats.work.newton_failures;
  diag.output_seconds = timed.output_seconds();
  diag.cpu_seconds = std::max(0.0, stats.cpu_seconds - diag.output_seconds);
  diag.status = stats.status;
  if (!stats.ok) {
    writer.abandon(diag);
    std::cerr << "lgi: " << scheme->name << " on " << scene.file << ": " << stats.status << "; partial trajectory kept in "
              << writer.partial_path() << '\n';
    return exit_run_failed;
  }
  writer.finish(diag);
  if (!o.quiet) {
    std::cout << "scheme=" << scheme->name << " steps=" << stats.steps << " rejected=" << stats.work.rejected_steps
              << " rhs_evaluations=" << stats.work.rhs_evaluations << " cpu_seconds=" << format_sci(diag.cpu_seconds)
              << " output_seconds=" << format_sci(diag.output_seconds)
              << " t_end=" << format_general(stats.t_final, 10) << ' ' << observer.invariant_error_summary() << '\n';
  }
  return exit_ok;
}

}  // namespace

Subcommand add_simulate_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<SimulateOptions>();
  auto* sub = app.add_subcommand("simulate", "Integrate one scene with one scheme and write an H5MD trajectory");
  add_scene_scheme_options(*sub, *o);
  sub->add_option("--save-every", o->save_every,
                  "Save every N steps; the initial and final states are always saved (a warning when the file would "
                  "exceed 100 MB)")
      ->capture_default_str();
  sub->add_option("--retry-halving", o->retry_halving,
                  "Fixed-step schemes: redo a step whose implicit solve did not converge as two half steps, at most "
                  "N halvings deep; each redone step counts in /diagnostics rejected_steps (and newton_failures)")
      ->capture_default_str();
  sub->add_option("--out", o->out, "Output trajectory file (HDF5, H5MD layout)")->required();
  add_force_quiet_flags(*sub, *o, "Overwrite an existing output file");
  return {sub, [o, context] {
            o->command_line = context.command_line;
            return simulate(*o);
          }};
}

}  // namespace lgi::experiments
