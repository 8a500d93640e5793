// lgi simulate: scene file → model → scheme → stepper loop → observer (HDF5).
#include <csignal>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "experiments/commands.hpp"
#include <memory>
#include <optional>
#include "experiments/exit_status.hpp"
#include "experiments/run_parameters.hpp"
#include "experiments/scene_reader.hpp"
#include "experiments/trajectory_observer.hpp"
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

extern "C" void request_interrupt(int) { interrupt_requested.store(true); }

std::string format_number(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

/// Validates flags against the scene and the scheme; fills the run config.
integrators::RunConfig run_config(const SimulateOptions& o, const system::Scene& scene,
                                  const integrators::SchemeInfo& scheme) {
  integrators::RunConfig cfg;
  cfg.t_end = o.t_end.value_or(scene.t_end);
  if (!(cfg.t_end >= 0.0) || !std::isfinite(cfg.t_end)) throw UsageError("--t-end: must be a finite number >= 0");
  if (o.save_every < 1) throw UsageError("--save-every: must be >= 1");
  cfg.save_every = o.save_every;
  if (o.dt && !(*o.dt > 0.0 && std::isfinite(*o.dt))) throw UsageError("--dt: must be a finite number > 0");
  if (o.tol && !(*o.tol > 0.0 && std::isfinite(*o.tol))) throw UsageError("--tol: must be a finite number > 0");
  if (scheme.properties.adaptive) {
    if (!o.tol && !scene.tol)
      throw UsageError("--tol: scheme '" + scheme.name + "' is adaptive and needs a tolerance: give --tol or [run] tol in " + scene.file);
    cfg.tol = o.tol ? *o.tol : *scene.tol;
    cfg.dt = o.dt.value_or(0.0);  // first trial step; 0 lets the scheme choose
  } else {
    if (o.tol) throw UsageError("--tol: scheme '" + scheme.name + "' is fixed-step; give --dt instead");
    if (!o.dt && !scene.dt)
      throw UsageError("--dt: scheme '" + scheme.name + "' needs a step: give --dt or [run] dt in " + scene.file);
    cfg.dt = o.dt ? *o.dt : *scene.dt;
  }
  if (o.retry_halving < 0 || o.retry_halving > 30) throw UsageError("--retry-halving: must be between 0 and 30");
  if (o.retry_halving > 0 && scheme.properties.adaptive)
    throw UsageError("--retry-halving: scheme '" + scheme.name + "' is adaptive and controls its own steps");
  cfg.retry_halving = o.retry_halving;
  return cfg;
}

int simulate(const SimulateOptions& o) {
  const system::Scene scene = read_scene(o.scene);
  const integrators::SchemeInfo* scheme = integrators::find_scheme(o.scheme);
  if (!scheme) throw UsageError("--scheme: unknown scheme '" + o.scheme + "' (lgi schemes lists them)");
  const integrators::RunConfig cfg = run_config(o, scene, *scheme);
  const system::AnyModel model = system::make_model(scene);
  if (const std::string why = integrators::unsupported_reason(*scheme, model); !why.empty())
    throw RunError(why + "; scene " + scene.file + " is not one");

  const system::SceneInvariants invariants(scene, model);
  const ResultAttributes run = run_parameters(scene, *scheme, cfg, o.command_line);
  Provenance prov{run.text, run.number, run.integer};
  prov.integer_attributes["save_every"] = cfg.save_every;
  if (cfg.retry_halving > 0) prov.integer_attributes["retry_halving"] = cfg.retry_halving;

  TrajectoryWriter writer(o.out, o.force, trajectory_layout(invariants, scheme->properties.euler_angle_chart), prov);
  TrajectoryObserver observer(invariants, &writer);

  interrupt_requested.store(false);
  auto previous_int = std::signal(SIGINT, request_interrupt);
  auto previous_term = std::signal(SIGTERM, request_interrupt);

  system::State state = scene.initial;
  integrators::RunStats stats;
  try {
    stats = scheme->run(model, state, cfg, observer);
  } catch (const Interrupted& e) {
    stats.ok = false;
    stats.status = e.what();
  }
  std::signal(SIGINT, previous_int);
  std::signal(SIGTERM, previous_term);

  Diagnostics diag;
  diag.steps = stats.steps;
  diag.rejected_steps = stats.work.rejected_steps;
  diag.rhs_evaluations = stats.work.rhs_evaluations;
  diag.newton_iterations_max = stats.work.newton_iterations_max;
  diag.newton_failures = stats.work.newton_failures;
  diag.cpu_seconds = stats.cpu_seconds;
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
              << " rhs_evaluations=" << stats.work.rhs_evaluations << " cpu_seconds=" << format_number(stats.cpu_seconds)
              << " t_end=" << format_number(stats.t_final) << ' ' << observer.invariant_error_summary() << '\n';
  }
  return exit_ok;
}

}  // namespace

Subcommand add_simulate_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<SimulateOptions>();
  auto* sub = app.add_subcommand("simulate", "Integrate one scene with one scheme and write an H5MD trajectory");
  sub->add_option("--scene", o->scene, "Scene file (TOML)")->required();
  sub->add_option("--scheme", o->scheme, "Scheme name (see `lgi schemes`)")->required();
  sub->add_option("--dt", o->dt,
                  "Step size (fixed-step schemes; first trial step of adaptive ones). Default: the scene's [run] dt");
  sub->add_option("--tol", o->tol, "Tolerance of adaptive schemes. Default: the scene's [run] tol");
  sub->add_option("--t-end", o->t_end, "Final time. Default: the scene's [run] t_end");
  sub->add_option("--save-every", o->save_every, "Save every N steps; the initial and final states are always saved")
      ->capture_default_str();
  sub->add_option("--retry-halving", o->retry_halving,
                  "Fixed-step schemes: redo a step whose implicit solve did not converge as two half steps, at most "
                  "N halvings deep; each redone step counts in /diagnostics rejected_steps (and newton_failures)")
      ->capture_default_str();
  sub->add_option("--out", o->out, "Output trajectory file (HDF5, H5MD layout)")->required();
  sub->add_flag("--force", o->force, "Overwrite an existing output file");
  sub->add_flag("--quiet", o->quiet, "Print nothing but errors");
  return {sub, [o, context] {
            o->command_line = context.command_line;
            return simulate(*o);
          }};
}

}  // namespace lgi::experiments
