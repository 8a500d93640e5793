// lgi simulate: scene file → model → scheme → stepper loop → observer (HDF5);
// the run itself is cli/simulation.hpp, which lgi.simulate (python/) shares.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "experiments/cli/cardan_simulation.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/simulation.hpp"
#include "experiments/cli/write_failures.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "integrators/registry/registry.hpp"

namespace lgi::experiments {
namespace {

struct SimulateOptions {
  std::string scene;
  std::string scheme;
  std::optional<double> dt;
  std::optional<double> tol;
  std::optional<double> t_end;
  std::int64_t save_every = 1;
  std::optional<double> output_dt;
  int retry_halving = 0;
  std::string out;
  bool force = false;
  bool quiet = false;
  std::string command_line;
};

SimulationRequest request_of(const SimulateOptions& o) {
  return {o.dt, o.tol, o.t_end, o.save_every, o.retry_halving, o.out, o.force, o.quiet, o.command_line, o.output_dt};
}

int simulate(const SimulateOptions& o) {
  const system::Scene scene = read_scene(o.scene);
  if (is_cardan_scene(scene) || is_cardan_scheme(o.scheme)) return simulate_cardan(scene, o.scheme, request_of(o));
  const integrators::SchemeInfo& scheme = scheme_by_name(o.scheme, "--scheme");
  const SimulationRequest request = request_of(o);
  const integrators::RunConfig cfg = simulation_config(request, scene, scheme);
  SimulationOutcome outcome;
  {
    const InterruptGuard interrupt_guard;
    outcome = run_simulation(scene, scheme, cfg, request, nullptr, &interrupt_requested);
  }
  if (!outcome.stats.ok) {
    std::cerr << "lgi: " << outcome.failure_message << '\n';
    return outcome.stats.interrupted ? interrupted_exit_status() : exit_run_failed;
  }
  if (!o.quiet) {
    const integrators::RunStats& stats = outcome.stats;
    std::cout << "scheme=" << scheme.name << " steps=" << stats.steps << " rejected=" << stats.work.rejected_steps
              << " rhs_evaluations=" << stats.work.rhs_evaluations
              << " cpu_seconds=" << format_sci(outcome.diagnostics.cpu_seconds)
              << " output_seconds=" << format_sci(outcome.diagnostics.output_seconds)
              << " t_end=" << format_general(stats.t_final, 10) << ' ' << outcome.error_summary << '\n';
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
  sub->add_option("--output-dt", o->output_dt,
                  "Save at t0, t0 + D, t0 + 2D, ... and t_end instead (not with --save-every): interpolated inside "
                  "the steps of a scheme with dense output (lgi schemes: dense), landed on by other adaptive schemes; "
                  "a fixed-step scheme needs D a whole multiple of its step");
  sub->add_option("--retry-halving", o->retry_halving,
                  "Fixed-step schemes: redo a step whose implicit solve did not converge as two half steps, at most "
                  "N halvings deep; each redone step counts in /diagnostics rejected_steps (and newton_failures)")
      ->capture_default_str();
  sub->add_option("--out", o->out, "Output trajectory file (HDF5, H5MD layout)")->required();
  add_force_quiet_flags(*sub, *o, "Overwrite an existing output file");
  sub->footer(exit_status_help);
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_with_write_failures_as_run_errors([&] { return simulate(*o); });
          },
          [o] {
            if (!is_cardan_scheme(o->scheme))  // a T^3 scheme (docs/cardan.md): checked with its scene
              check_simulation_flags(request_of(*o), scheme_by_name(o->scheme, "--scheme"));
          }};
}

}  // namespace lgi::experiments
