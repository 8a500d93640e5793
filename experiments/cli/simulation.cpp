#include "experiments/cli/simulation.hpp"

#include <sys/statvfs.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "experiments/cli/output_grid.hpp"
#include "experiments/cli/run_parameters.hpp"
#include "experiments/cli/step_settings.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/output_timing.hpp"

namespace lgi::experiments {
namespace {

/// Refuses a trajectory larger than the free space of its file system (README.md, "Limits";
/// statvfs's space for unprivileged users), even with --quiet: the .partial is renamed, not copied.
void refuse_if_it_cannot_fit(const std::string& path, double bytes, const std::string& flag) {
  struct statvfs fs {};
  if (::statvfs(hdf5::parent_directory(path).c_str(), &fs) != 0) return;  // the create reports what is wrong
  const double free_bytes = static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
  if (bytes <= free_bytes) return;
  throw OutputFileError("--out: " + path + ": the samples need about " + format_general(std::ceil(bytes / 1e9), 6) +
                        " GB and the file system has " + format_general(std::floor(free_bytes / 1e9), 6) +
                        " GB free; give " + flag + " for fewer samples");
}

/// About 128 bytes a sample (time, step, quaternion, Pi, Omega, energy,
/// invariants); a file over 100 MB deserves a word before it is written,
/// and one larger than the free space is refused.
void warn_if_large(const integrators::RunConfig& cfg, const system::SceneInvariants& invariants, bool adaptive,
                   bool quiet, const std::string& path) {
  if (!cfg.output_times && (adaptive || cfg.dt <= 0.0)) return;
  const double samples = cfg.output_times
                             ? static_cast<double>(cfg.output_times->size())
                             : static_cast<double>(integrators::fixed_step_count(cfg.t_end - cfg.t0, cfg.dt)) /
                                       static_cast<double>(cfg.save_every) + 1.0;
  const double bytes_per_sample = 8.0 * (16.0 + static_cast<double>(invariants.scalar_names().size()));
  const double megabytes = samples * bytes_per_sample / 1e6;
  refuse_if_it_cannot_fit(path, samples * bytes_per_sample, cfg.output_times ? "a larger --output-dt" : "--save-every N");
  if (quiet || megabytes < 100.0) return;
  if (cfg.output_times)
    std::cerr << "lgi: warning: --output-dt writes " << format_general(samples, 3) << " samples, about "
              << format_general(megabytes, 3) << " MB; give a larger --output-dt for fewer\n";
  else
    std::cerr << "lgi: warning: --save-every " << cfg.save_every << " writes " << format_general(samples, 3)
              << " samples, about " << format_general(megabytes, 3)
              << " MB; give --save-every N to keep every N-th step\n";
}

Provenance run_provenance(const system::Scene& scene, const integrators::SchemeInfo& scheme,
                          const integrators::RunConfig& cfg, const SimulationRequest& request) {
  const ResultAttributes run = run_parameters(scene, scheme, cfg, request.command_line);
  Provenance prov{run.text, run.number, run.integer};
  prov.integer_attributes["save_every"] = cfg.save_every;
  if (request.output_dt) prov.number_attributes["output_dt"] = *request.output_dt;
  if (cfg.retry_halving > 0) prov.integer_attributes["retry_halving"] = cfg.retry_halving;
  return prov;
}

Diagnostics diagnostics_of(integrators::RunStats& stats, double output_seconds) {
  // Reported as it always was; the statistics are the loop's own.
  if (stats.interrupted) stats.status = integrators::interrupted_status;
  return diagnostics_of_run(stats, output_seconds);
}

}  // namespace

void check_simulation_flags(const SimulationRequest& request, const integrators::SchemeInfo& scheme) {
  if (request.save_every < 1) throw UsageError("--save-every: must be >= 1");
  check_step_flags({request.dt, request.tol, request.t_end}, /*allow_zero_t_end=*/true);
  if (request.retry_halving < 0 || request.retry_halving > 30)
    throw UsageError("--retry-halving: must be between 0 and 30");
  if (request.retry_halving > 0 && scheme.properties.adaptive)
    throw UsageError("--retry-halving: scheme '" + scheme.name + "' is adaptive and controls its own steps");
  if (request.output_dt) check_output_dt_flag(*request.output_dt, request.save_every);
}

integrators::RunConfig simulation_config(const SimulationRequest& request, const system::Scene& scene,
                                         const integrators::SchemeInfo& scheme) {
  check_simulation_flags(request, scheme);
  integrators::RunConfig cfg =
      resolve_run_config({request.dt, request.tol, request.t_end}, scene, scheme, /*allow_zero_t_end=*/true);
  cfg.save_every = request.save_every;
  cfg.retry_halving = request.retry_halving;
  if (request.output_dt) check_output_dt(*request.output_dt, cfg, scheme);
  return cfg;
}

void check_scheme_supports(const integrators::SchemeInfo& scheme, const system::Scene& scene,
                           const system::AnyModel& model) {
  if (const std::string why = integrators::unsupported_reason(scheme, model); !why.empty())
    throw UsageError("--scheme: " + why + "; scene " + scene.file + " is not one");
  if (scene.suspension)  // the SO(3) run path: a Cardan scene goes to run_cardan_simulation (cardan_simulation.hpp)
    throw UsageError("--scheme: " + scheme.name + " runs on SO(3) x R^3 scenes only (scene " + scene.file +
                     " is a Cardan top, state on T^3 x R^3): use a cardan-* scheme");
}

void close_simulation(SimulationOutcome& outcome, const std::string& scheme_name, const std::string& scene_file,
                      TrajectoryWriter* writer) {
  if (outcome.stats.ok) {
    if (writer) writer->finish(outcome.diagnostics);
    return;
  }
  outcome.failure_message = scheme_name + " on " + scene_file + ": " + outcome.stats.status;
  if (writer) {
    writer->abandon(outcome.diagnostics);
    outcome.failure_message += "; partial trajectory kept in " + writer->partial_path();
  }
}

SimulationOutcome run_simulation(const system::Scene& scene, const integrators::SchemeInfo& scheme,
                                 const integrators::RunConfig& cfg, const SimulationRequest& request,
                                 SampleSink* sink, const std::atomic<bool>* stop) {
  const system::AnyModel model = system::make_model(scene);
  check_scheme_supports(scheme, scene, model);
  const system::SceneInvariants invariants(scene, model);
  integrators::RunConfig c = cfg;
  std::vector<double> times;  // --output-dt's sample times, which c points to
  if (request.output_dt) {
    times = output_grid(cfg.t0, cfg.t_end, *request.output_dt);
    c.output_times = &times;
  }
  std::optional<TrajectoryWriter> writer;
  if (!request.out.empty()) {
    warn_if_large(c, invariants, scheme.properties.adaptive, request.quiet, request.out);
    writer.emplace(request.out, request.force, trajectory_layout(invariants, scheme.properties.euler_angle_chart),
                   run_provenance(scene, scheme, c, request));
  }
  TrajectoryObserver observer(invariants, writer ? &*writer : nullptr, sink);
  OutputTimingObserver timed(observer);

  system::State state = scene.initial;
  SimulationOutcome outcome;
  c.stop = stop;  // every loop (the baselines' too) ends cleanly, with its statistics
  outcome.stats = scheme.run(model, state, c, timed);
  outcome.diagnostics = diagnostics_of(outcome.stats, timed.output_cpu_seconds(outcome.stats.cpu_seconds));
  outcome.error_summary = observer.invariant_error_summary();
  close_simulation(outcome, scheme.name, scene.file, writer ? &*writer : nullptr);
  return outcome;
}

}  // namespace lgi::experiments
