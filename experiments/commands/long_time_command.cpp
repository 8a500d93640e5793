// lgi long-time: invariant errors over very long runs (10⁶–10⁸ steps).
//
// The observer is called at every step (save_every = 1). It evaluates the
// scene's invariants, keeps the running maximum of every error since the last
// sample (so spikes between samples are not lost), and emits one row at the
// sample steps only: step 0, then about N steps per decade, log-spaced
// (round(10^(j/N)), j = 0, 1, ...), and the last step. Rows go to the
// results file (RESULTS.md, /series), which writes them in blocks and
// flushes at least every 2 s: a killed run leaves a readable .partial.
//
// Ctrl-C (SIGINT, also SIGTERM) stops the run at the next step boundary: a
// row for that step is written, /diagnostics status "interrupted by signal",
// the files are kept as <out>.partial (said on stderr), exit status 130
// (SIGINT) or 143 (SIGTERM).
//
// --resume goes on from the last checkpoint in <out>.partial, bit for bit as
// if the run had never stopped (long_time/long_time_resume.hpp; RESULTS.md,
// "long-time --resume"). With a scheme that can be resumed, rows reach the
// file with the checkpoints, at most every --flush-seconds.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include "experiments/analysis/cardan_invariants.hpp"
#include "experiments/cli/cardan_simulation.hpp"
#include "experiments/cli/work_limits.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/commands/long_time/long_time_observer.hpp"
#include "experiments/commands/long_time/long_time_resume.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/cli/run_parameters.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/step_settings.hpp"
#include "experiments/cli/write_failures.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/output_timing.hpp"
#include "experiments/io/results_file.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "integrators/registry/registry.hpp"
#include "integrators/system/invariants.hpp"

namespace lgi::experiments {
namespace {

struct LongTimeOptions {
  std::string scene;
  std::string scheme;
  std::optional<double> dt;
  std::optional<double> tol;
  std::optional<double> t_end;
  int samples = 20;
  double flush_seconds = 2.0;
  std::string out;
  bool force = false;
  bool quiet = false;
  bool resume = false;
  std::string command_line;
};

/// The one parseable line (and the files written) of a finished run.
template <class Observer>
void print_summary(const std::string& scheme, const Diagnostics& diag, double t_final,
                   const std::vector<std::string>& names, const Observer& observer, const ResultsFile& file) {
  std::ostringstream line;
  line << "scheme=" << scheme << " steps=" << diag.steps << " samples=" << file.rows()
       << " cpu_seconds=" << format_sci(diag.cpu_seconds) << " output_seconds=" << format_sci(diag.output_seconds)
       << " t_end=" << format_general(t_final, 10);
  for (std::size_t i = 0; i < names.size(); ++i)
    line << ' ' << names[i] << "_end=" << format_sci(observer.current()[i]) << ' ' << names[i]
         << "_max=" << format_sci(observer.run_max()[i]);
  std::cout << line.str() << '\n';
  std::cout << "wrote " << file.path() << " and " << file.csv_path() << '\n';
}

/// /diagnostics of a run (RESULTS.md, "long-time").
ResultAttributes long_time_diagnostics(const integrators::RunStats& stats, double output_seconds,
                                       std::int64_t rows, Diagnostics& diag) {
  diag = diagnostics_of_run(stats, output_seconds);
  ResultAttributes a = diagnostics_attributes(diag);
  a.integer["samples"] = rows;
  a.number["t_final"] = stats.t_final;
  return a;
}

/// The checks that need no scene (CommandLine::parse runs them first).
void check_long_time_flags(const LongTimeOptions& o) {
  if (!is_cardan_scheme(o.scheme)) (void)scheme_by_name(o.scheme, "--scheme");  // a T^3 scheme: checked with its scene
  if (o.samples < 1) throw UsageError("--samples: must be >= 1 (samples per decade of steps)");
  check_work_limit("--samples", o.samples, max_samples_per_decade, "samples per decade");
  if (!(o.flush_seconds > 0.0) || !std::isfinite(o.flush_seconds))
    throw UsageError("--flush-seconds: must be a finite number > 0");
  check_step_flags({o.dt, o.tol, o.t_end}, /*allow_zero_t_end=*/false);
}

/// The results file: new, or (--resume) reopened at its last checkpoint.
template <class S>
ResumedResults<S> open_results(const LongTimeOptions& o, const system::Scene& scene,
                               const integrators::SchemeInfo& scheme, const integrators::RunConfig& cfg,
                               std::int64_t last_step, const std::vector<Column>& columns,
                               std::size_t error_columns) {
  ResultsFileOptions options;
  options.table = "series";
  options.flush_interval_seconds = o.flush_seconds;
  const std::string fingerprint = long_time_fingerprint(scene, scheme, cfg, o.samples, columns);
  if (o.resume) {
    if (!scheme.resumable)
      throw UsageError("--resume: scheme '" + scheme.name +
                       "' keeps memory between steps that lgi cannot save yet; run it again without --resume");
    ResumedResults<S> r = reopen_for_resume<S>(o.out, o.force, columns, options, fingerprint, error_columns);
    if (!r.file) {
      if (!o.quiet)
        std::cerr << "lgi: " << o.out << ".partial holds no checkpoint (a run killed as it started): starting "
                  << "again from step 0\n";
      LongTimeOptions fresh = o;
      fresh.resume = false;
      fresh.force = true;  // the partial files are replaced; the finished ones were checked above
      return open_results<S>(fresh, scene, scheme, cfg, last_step, columns, error_columns);
    }
    // An intact checkpoint of this run lies inside it (a damaged one cannot pass its hash, but says so here too).
    if (const auto& c = r.checkpoint;
        c && (c->loop.step < 1 || (last_step > 0 && c->loop.step >= last_step) || !(c->loop.t > cfg.t0) ||
              !(c->loop.t < cfg.t_end) || !std::isfinite(c->loop.h)))
      throw OutputFileError("cannot resume results '" + r.file->partial_path() +
                            "': its checkpoint does not fit this run (damaged)");
    if (!o.quiet)
      std::cerr << "lgi: resuming " << r.file->partial_path()
                << (r.checkpoint ? " from step " + std::to_string(r.checkpoint->loop.step) + ", t = " +
                                       format_general(r.checkpoint->loop.t, 10)
                                 : std::string(" from step 0 (no checkpoint in it yet)"))
                << '\n';
    return r;
  }
  ResumedResults<S> r;
  r.file = std::make_unique<ResultsFile>(o.out, o.force, columns, options);
  ResultAttributes params = run_parameters(scene, scheme, cfg, o.command_line);
  params.text["subcommand"] = "long-time";
  params.integer["samples_per_decade"] = o.samples;
  r.file->write_parameters(params);
  create_resume_record(*r.file, fingerprint);
  return r;
}

/// The run after its settings are resolved, on states S: `run(state, cfg,
/// observer)` runs the scheme on the scene's model from `initial`.
template <class S, class Invariants, class Run>
int run_long_time(const LongTimeOptions& o, const system::Scene& scene, const integrators::SchemeInfo& scheme,
                  const integrators::RunConfig& settings, std::int64_t last_step, const Invariants& invariants,
                  const S& initial, Run&& run) {
  std::vector<std::string> names;  // the error columns, e.g. "energy_error"
  for (const auto& n : invariants.error_names()) names.push_back(n + "_error");
  std::vector<Column> columns = {{"step", ColumnType::integer, ""}, {"time", ColumnType::real, "s"}};
  for (const auto& n : names) columns.push_back({n, ColumnType::real, ""});
  for (const auto& n : names) columns.push_back({n + "_window_max", ColumnType::real, ""});

  // From before <out>.partial exists until the results are published, a
  // signal only sets the flag: the loop stops at a step boundary, and one
  // that comes after the last step lets the files be finished (exit 0).
  const InterruptGuard interrupt_guard;
  ResumedResults<S> opened = open_results<S>(o, scene, scheme, settings, last_step, columns, names.size());
  ResultsFile& file = *opened.file;
  const std::optional<BasicRunCheckpoint<S>>& from = opened.checkpoint;

  Progress progress(!o.quiet && ::isatty(STDERR_FILENO) == 1);
  LongTimeObserver<S, Invariants> observer(invariants, file, names, o.samples, last_step, settings.t0,
                                           settings.t_end, progress);
  BasicOutputTimingObserver<S> timed(observer);
  const double cpu_before = from ? from->cpu_seconds : 0.0, output_before = from ? from->output_seconds : 0.0;
  const double cpu_start = integrators::detail::cpu_now();
  LongTimeCheckpoints<S> checkpoints(
      file, o.flush_seconds,
      [&](BasicRunCheckpoint<S>& c) {
        observer.fill(c);
        const double cpu_run = integrators::detail::cpu_now() - cpu_start;
        c.cpu_seconds = cpu_before + cpu_run;
        c.output_seconds = output_before + timed.output_cpu_seconds(cpu_run);
      },
      opened.next_sequence);
  integrators::BasicRunConfig<S> cfg = integrators::run_config_with<S>(settings);
  if (scheme.resumable) {
    cfg.checkpoints = &checkpoints;
    observer.flush_with_checkpoints();
  }
  if (from) {
    checkpoints.resume_from = &from->loop;
    observer.resume_at(*from, initial);
  }

  S state = initial;
  integrators::RunStats stats;
  bool interrupted = false;
  {
    cfg.stop = &interrupt_requested;  // every loop (the baselines' too) ends cleanly, with its statistics
    stats = run(state, cfg, timed);
    if (stats.interrupted) {  // reported as before, with the loop's own statistics
      interrupted = true;
      stats.status = integrators::interrupted_status;
    }
  }
  progress.done();
  observer.finish();
  const double output_seconds = output_before + timed.output_cpu_seconds(stats.cpu_seconds);
  stats.cpu_seconds += cpu_before;

  Diagnostics diag;
  const ResultAttributes diag_attributes = long_time_diagnostics(stats, output_seconds, file.rows(), diag);
  if (!stats.ok) {
    file.abandon(diag_attributes);
    std::cerr << "lgi: " << scheme.name << " on " << scene.file << ": " << stats.status
              << (interrupted ? " at step " + std::to_string(stats.steps) : std::string())
              << "; results so far kept in " << file.partial_path() << " and " << file.csv_partial_path()
              << (scheme.resumable ? " (--resume goes on from the last checkpoint)" : "") << '\n';
    return interrupted ? interrupted_exit_status() : exit_run_failed;
  }
  file.finish(diag_attributes);
  if (!o.quiet) print_summary(scheme.name, diag, stats.t_final, names, observer, file);
  return exit_ok;
}

int long_time(const LongTimeOptions& o) {
  const system::Scene scene = read_scene(o.scene);
  // A Cardan scene runs a scheme of T^3 x R^3, any other one of SO(3) x R^3 (cardan_simulation.hpp).
  const integrators::SchemeInfo& scheme = scheme_for_scene(scene, o.scheme, "--scheme");
  check_long_time_flags(o);
  // The command line, then the scene's [run] (step_settings.hpp).
  integrators::RunConfig settings =
      resolve_run_config({o.dt, o.tol, o.t_end}, scene, scheme, /*allow_zero_t_end=*/false);
  settings.save_every = 1;
  const std::int64_t last_step =
      scheme.properties.adaptive ? 0 : integrators::fixed_step_count(settings.t_end - settings.t0, settings.dt);
  if (is_cardan_scene(scene)) {
    const system::CardanTop top = cardan_top(scene);
    const CardanInvariants invariants(top);
    return run_long_time(o, scene, scheme, settings, last_step, invariants, scene.cardan_initial,
                         [&](system::TorusState& x, const integrators::TorusRunConfig& cfg,
                             integrators::TorusObserver& observer) { return scheme.run_cardan(top, x, cfg, observer); });
  }
  const system::AnyModel model = system::make_model(scene);
  if (const std::string why = integrators::unsupported_reason(scheme, model); !why.empty())
    throw RunError(why + "; scene " + scene.file + " is not one");
  const system::SceneInvariants invariants(scene, model);
  return run_long_time(o, scene, scheme, settings, last_step, invariants, scene.initial,
                       [&](system::State& x, const integrators::RunConfig& cfg, integrators::Observer& observer) {
                         return scheme.run(model, x, cfg, observer);
                       });
}

}  // namespace

Subcommand add_long_time_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<LongTimeOptions>();
  auto* sub = app.add_subcommand(
      "long-time",
      "Invariant errors over very long runs: log-spaced samples in the step number and, for each window between "
      "samples, the largest error");
  add_scene_scheme_options(*sub, *o);
  sub->add_option("--samples", o->samples, "Samples per decade of steps (plus the first and the last step)")
      ->capture_default_str();
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV goes beside it, .csv in place of .h5 (out.h5 -> out.csv)")->required();
  sub->add_flag("--resume", o->resume,
                "Go on from the last checkpoint in <out>.partial, left by a run with the same arguments that was "
                "killed or stopped: the same rows, bit for bit, as a run never stopped");
  sub->add_option("--flush-seconds", o->flush_seconds,
                  "Rows (and the checkpoint --resume goes on from) reach the file at least this often")
      ->capture_default_str();
  add_force_quiet_flags(*sub, *o, "Overwrite existing output files");
  sub->footer(exit_status_help);
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_with_write_failures_as_run_errors([&] { return long_time(*o); });
          },
          [o] { check_long_time_flags(*o); }};
}

}  // namespace lgi::experiments
