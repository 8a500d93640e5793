// lgi frequencies --scene FILE --t-end T [--observable NAME[,NAME...]] [--terms K] [--window-order P]
//   [--scheme S] [--dt H] [--output-dt D] [--tol TOL] [--state-file F] [--threads N] --out FILE.h5 [--force] [--quiet]
// Laskar's frequency analysis (NAFF) of chosen observables along the scene's
// trajectory (experiments/FREQUENCIES.md, docs/frequency_analysis.md): the
// run samples them at t0 + k D (analysis/frequency/observable_series.hpp),
// NAFF gives K terms each (naff.hpp), and the two halves of the run the
// diffusion index (frequency_diffusion.hpp). A Cardan top (T³ × ℝ³) is sampled by a
// fixed-step T³ scheme (cardan_series.hpp), from its initial state or each row of --state-file.
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <numbers>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/analysis/frequency/cardan_series.hpp"
#include "experiments/analysis/frequency/observable_frequencies.hpp"
#include "experiments/cli/cardan_simulation.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/thread_count.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "experiments/io/state_file.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "integrators/core/run_config.hpp"  // interrupted_status
#include "integrators/system/model.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

namespace fq = frequency;

struct FrequenciesOptions {
  std::string scene, out, scheme, state_file;  // scheme "": split-symmetric@kahan-li8, cardan-rk4 on a Cardan top
  std::optional<double> t_end, dt, output_dt, tol;
  std::vector<std::string> observables;
  int terms = 5, window_order = 1, threads = 0;
  bool force = false, quiet = false;
  std::string command_line;
};

std::string shown(double x) { return format_general(x, 12); }  // in messages

void check_flags(const FrequenciesOptions& o) {
  if (!o.t_end || !(*o.t_end > 0.0) || !std::isfinite(*o.t_end)) throw UsageError("--t-end: must be a positive number");
  for (const auto* v : {&o.dt, &o.output_dt, &o.tol})
    if (*v && (!(**v > 0.0) || !std::isfinite(**v)))
      throw UsageError(std::string(v == &o.dt ? "--dt" : v == &o.output_dt ? "--output-dt" : "--tol") +
                       ": must be a positive number");
  if (o.terms < 1 || o.terms > 100) throw UsageError("--terms: must be between 1 and 100");
  if (o.window_order < 0 || o.window_order > 8) throw UsageError("--window-order: must be between 0 and 8");
  try {
    fq::components_of(o.observables);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--observable: ") + e.what());
  }
}

/// The sampling of the run, checked against the scheme (the flags named in the refusals).
fq::SamplingSettings sampling(const FrequenciesOptions& o, const system::Scene& scene,
                              const integrators::SchemeInfo& scheme) {
  fq::SamplingSettings s;
  s.t_end = *o.t_end;
  s.dt = o.dt ? *o.dt : scene.dt.value_or(0.0);
  if (!(s.dt > 0.0)) throw UsageError("--dt: missing, and the scene " + scene.file + " has no [run] dt");
  s.tol = o.tol ? *o.tol : scene.tol.value_or(1e-10);
  s.output_dt = o.output_dt.value_or(s.dt);
  const double ratio = s.output_dt / s.dt;
  if (!scheme.properties.adaptive && (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio || ratio < 0.5))
    throw UsageError("--output-dt: " + shown(s.output_dt) + " is not a whole multiple of the step " + shown(s.dt) +
                     " of the fixed-step scheme " + scheme.name);
  const double samples = std::floor(s.t_end / s.output_dt * (1.0 + 1e-12)) + 1.0;
  if (samples < 16.0 || samples > 1e8)
    throw UsageError("--t-end: " + shown(s.t_end) + " holds " + shown(samples) + " output times of --output-dt " +
                     shown(s.output_dt) + "; frequency analysis needs 16 to 1e8");
  if (const std::string why = integrators::unsupported_reason(scheme, system::make_model(scene)); !why.empty())
    throw UsageError("--scheme: " + why + "; scene " + scene.file + " is not one");
  return s;
}

/// The records of each state (index 0: the scene's initial state, else the state file's row).
using StateRecords = std::vector<std::vector<fq::ObservableFrequencies>>;

std::vector<TableColumn> term_columns(const StateRecords& states) {
  std::vector<TableColumn> c = {{"observable"}, {"term", 1, true}, {"frequency"}, {"amplitude"},
                                {"phase"},      {"period"},         {"diffusion"}, {"index", 1, true}};
  c[0].is_text = true;
  for (std::size_t i = 0; i < states.size(); ++i)
    for (const auto& r : states[i])
    for (std::size_t k = 0; k < r.terms.terms.size(); ++k) {
      const fq::NaffTerm& t = r.terms.terms[k];
      c[0].text.push_back(r.observable);
      c[1].whole.push_back(static_cast<std::int64_t>(k));
      c[2].real.push_back(t.frequency);
      c[3].real.push_back(t.amplitude);
      c[4].real.push_back(t.phase);
      c[5].real.push_back(2.0 * std::numbers::pi / std::abs(t.frequency));
      c[6].real.push_back(r.diffusion.log10_relative_change);  // the observable's, on each of its rows
      c[7].whole.push_back(static_cast<std::int64_t>(i));
    }
  return c;
}

TableGroup diffusion_group(const StateRecords& states) {
  TableGroup g{"frequency_diffusion"};
  g.columns = {{"observable"}, {"frequency"}, {"frequency_first_half"}, {"frequency_second_half"},
               {"relative_change"}, {"log10_relative_change"}, {"mean"}, {"index", 1, true}};
  g.columns[0].is_text = true;
  for (std::size_t i = 0; i < states.size(); ++i)
    for (const auto& r : states[i]) {
    g.columns[0].text.push_back(r.observable);
    g.columns[1].real.push_back(r.terms.terms.empty() ? std::nan("") : r.terms.terms[0].frequency);
    g.columns[2].real.push_back(r.diffusion.first_half);
    g.columns[3].real.push_back(r.diffusion.second_half);
    g.columns[4].real.push_back(r.diffusion.relative_change);
    g.columns[5].real.push_back(r.diffusion.log10_relative_change);
    g.columns[6].real.push_back(r.terms.mean.real());
    g.columns[7].whole.push_back(static_cast<std::int64_t>(i));
  }
  g.attributes["diffusion"] = "the leading frequency on [t0, t0 + T/2] and [t0 + T/2, t0 + T] (Laskar 1993)";
  return g;
}

void print_records(const std::vector<fq::ObservableFrequencies>& records) {
  for (const auto& r : records) {
    std::printf("%s:", r.observable.c_str());
    for (const auto& t : r.terms.terms) std::printf(" %.15g (%.3g)", t.frequency, t.amplitude);
    std::printf("  diffusion log10 = %.3g\n", r.diffusion.log10_relative_change);
  }
}

/// The sampling of a Cardan run (fixed-step T³ schemes only; the flags named in the refusals).
fq::SamplingSettings cardan_sampling(const FrequenciesOptions& o, const system::Scene& scene,
                                     const integrators::SchemeInfo& scheme) {
  if (scheme.properties.adaptive)
    throw UsageError("--scheme: " + scheme.name + " is adaptive; lgi frequencies samples a Cardan top with a "
                     "fixed-step scheme (cardan-rk4, cardan-midpoint, cardan-dg)");
  fq::SamplingSettings s;
  s.t_end = *o.t_end;
  s.dt = o.dt ? *o.dt : scene.dt.value_or(0.0);
  if (!(s.dt > 0.0)) throw UsageError("--dt: missing, and the scene " + scene.file + " has no [run] dt");
  s.output_dt = o.output_dt.value_or(s.dt);
  const double ratio = s.output_dt / s.dt;
  if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio || ratio < 0.5)
    throw UsageError("--output-dt: " + shown(s.output_dt) + " is not a whole multiple of the step " + shown(s.dt));
  const double samples = std::floor(s.t_end / s.output_dt * (1.0 + 1e-12)) + 1.0;
  if (samples < 16.0 || samples > 1e8)
    throw UsageError("--t-end: " + shown(s.t_end) + " holds " + shown(samples) + " output times of --output-dt " +
                     shown(s.output_dt) + "; frequency analysis needs 16 to 1e8");
  return s;
}

/// Every component must be one of the scene's kind (SO(3) or Cardan).
void check_observables(const std::vector<std::string>& names, bool cardan) {
  const auto& allowed = cardan ? fq::cardan_observable_names() : fq::observable_names();
  for (const auto& c : fq::components_of(names))
    if (std::find(allowed.begin(), allowed.end(), c) == allowed.end())
      throw UsageError("--observable: '" + c + "' is " + (cardan ? "not" : "only") + " an observable of a Cardan top" +
                       (cardan ? " (cardan_angle_1..3, cardan_momentum_1..3, cos_cardan_angle_1..3, "
                                 "sin_cardan_angle_1..3)"
                               : "; the scene is an SO(3) scene"));
}

struct Analysis {
  StateRecords states;
  std::string scheme, source;
  fq::SamplingSettings s;
  std::size_t samples = 0;
  int threads = 1;
  int exit = exit_ok;  // exit_run_failed or the interrupt's status where a run failed
};

/// A Cardan top: each state (the scene's, or each row of --state-file) run and analysed on one of
/// `threads` OpenMP threads, so the records do not depend on the count.
Analysis analyse_cardan(const FrequenciesOptions& o, const system::Scene& scene, const std::vector<std::string>& names,
                        int threads) {
  const std::string name = o.scheme.empty() ? "cardan-rk4" : o.scheme;
  const integrators::SchemeInfo* scheme = &scheme_for_scene(scene, name, "--scheme");
  Analysis a;
  a.scheme = scheme->name;
  a.s = cardan_sampling(o, scene, *scheme);
  const std::vector<system::TorusState> x0 =
      o.state_file.empty() ? std::vector<system::TorusState>{scene.cardan_initial} : read_cardan_state_file(o.state_file);
  a.source = o.state_file.empty() ? "the scene's initial state" : o.state_file;
  hdf5::check_output_target(o.out, o.force);
  const system::CardanTop top = cardan_top(scene);
  const std::vector<std::string> components = fq::components_of(names);
  a.states.resize(x0.size());
  a.threads = threads;
  std::vector<std::string> failures(x0.size());
  const auto n = static_cast<std::int64_t>(x0.size());
  // Progress on stderr (cli/sweep_progress.hpp; issue 50, item 8): in place on a terminal, else every 10 s.
  SweepProgress progress(o.quiet, n, 0, "frequencies", "states");
  std::int64_t finished = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (interrupt_requested.load()) continue;
    const fq::SampledRun run = fq::sample_cardan_observables(top, *scheme, a.s, x0[k], components, &interrupt_requested);
    if (!run.stats.ok) {
      failures[k] = run.stats.interrupted ? "interrupted" : run.stats.status;
      continue;
    }
    try {  // the analysis reads the flag too (NaffOptions::stop); an exception may not leave the loop
      a.states[k] = fq::observable_frequencies(run, names, {o.terms, o.window_order, &interrupt_requested}, 1);
    } catch (const fq::NaffStopped&) {
      failures[k] = "interrupted";
      continue;
    }
#pragma omp critical(lgi_frequencies_samples)
    {
      a.samples = run.series[0].size();
      progress.update(++finished, 0);
    }
  }
  progress.finish();
  for (std::size_t k = 0; k < failures.size(); ++k)
    if (!failures[k].empty() || interrupt_requested.load()) {
      std::cerr << "lgi: " << scheme->name << " on " << scene.file << ", state " << k << ": "
                << (failures[k].empty() ? "interrupted" : failures[k]) << '\n';
      a.exit = interrupt_requested.load() ? interrupted_exit_status() : exit_run_failed;
      return a;
    }
  return a;
}

Analysis analyse_so3(const FrequenciesOptions& o, const system::Scene& scene, const std::vector<std::string>& names,
                     int threads) {
  if (!o.state_file.empty()) throw UsageError("--state-file: Cardan scenes only; " + scene.file + " is an SO(3) scene");
  const integrators::SchemeInfo& scheme = scheme_by_name(o.scheme.empty() ? "split-symmetric@kahan-li8" : o.scheme,
                                                         "--scheme");
  Analysis a;
  a.scheme = scheme.name;
  a.source = "the scene's initial state";
  a.s = sampling(o, scene, scheme);
  a.threads = threads;
  hdf5::check_output_target(o.out, o.force);
  // The run reads the flag every step, its NAFF every 2^16 samples of each pass (naff.hpp); a signal
  // in either ends the command with nothing written (the file is written only at the end).
  const fq::SampledRun run = fq::sample_observables(scene, scheme, a.s, fq::components_of(names), &interrupt_requested);
  // One state: its line comes when the run is done (the same line as a Cardan top's states).
  SweepProgress progress(o.quiet, 1, 0, "frequencies", "states");
  if (run.stats.ok) progress.update(1, 0);
  progress.finish();
  if (!run.stats.ok) {
    std::cerr << "lgi: " << scheme.name << " on " << scene.file << ": " << run.stats.status << '\n';
    a.exit = run.stats.interrupted ? interrupted_exit_status() : exit_run_failed;
    return a;
  }
  a.samples = run.series[0].size();
  try {
    a.states = {fq::observable_frequencies(run, names, {o.terms, o.window_order, &interrupt_requested}, threads)};
  } catch (const fq::NaffStopped&) {
    std::cerr << "lgi: frequencies: " << integrators::interrupted_status << " in the frequency analysis of "
              << a.samples << " samples; nothing written\n";
    a.exit = interrupted_exit_status();
  }
  return a;
}

int run_frequencies(const FrequenciesOptions& o) {
  check_flags(o);
  const system::Scene scene = read_scene(o.scene);
  const bool cardan = scene.suspension.has_value();
  const std::vector<std::string> names =
      o.observables.empty() ? (cardan ? fq::cardan_observable_names() : fq::observable_names()) : o.observables;
  check_observables(names, cardan);
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  const auto start = std::chrono::steady_clock::now();
  // Ctrl-C / SIGTERM set the flag from here until the file is written (interrupt_guard.hpp).
  const InterruptGuard interrupt_guard;
  const Analysis a = cardan ? analyse_cardan(o, scene, names, threads) : analyse_so3(o, scene, names, threads);
  if (a.exit != exit_ok) return a.exit;
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::map<std::string, std::string> parameters = {
      {"subcommand", "frequencies"}, {"command_line", o.command_line}, {"scene_file", scene.file},
      {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
      {"cxx_flags", build_info::cxx_flags}, {"scheme", a.scheme}, {"t_end", format_exact(a.s.t_end)},
      {"dt", format_exact(a.s.dt)}, {"output_dt", format_exact(a.s.output_dt)}, {"samples", std::to_string(a.samples)},
      {"terms", std::to_string(o.terms)}, {"window_order", std::to_string(o.window_order)},
      {"states", a.source}, {"state_count", std::to_string(a.states.size())},
      {"method", "NAFF (Laskar 1990, 1993): window chi_p, FFT peak, Brent, zero of the derivative, Gram-Schmidt; "
                 "real signals as c + sum A cos(w (t - t0) + phi), w > 0; docs/frequency_analysis.md"},
      {"threads", std::to_string(threads)}, {"wall_seconds", format_general(wall, 6)}};
  write_table_file(o.out, o.force, "frequencies", term_columns(a.states), parameters, {diffusion_group(a.states)});
  if (o.quiet) return exit_ok;
  if (a.states.size() == 1) print_records(a.states[0]);
  std::cout << a.states.size() << (a.states.size() == 1 ? " state, " : " states, ") << a.samples
            << " samples to t = " << format_general(a.s.t_end, 10) << "; wrote " << o.out << '\n';
  return exit_ok;
}

}  // namespace

Subcommand add_frequencies_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<FrequenciesOptions>();
  auto* sub = app.add_subcommand(
      "frequencies",
      "Laskar's frequency analysis (NAFF) of observables along the scene's trajectory, with the diffusion index of "
      "the run's two halves (experiments/FREQUENCIES.md)");
  sub->add_option("--scene", o->scene, "Scene file (TOML): an SO(3) scene or a Cardan top ([suspension])")->required();
  sub->add_option("--t-end", o->t_end, "Length of the run T")->required();
  sub->add_option("--observable", o->observables,
                  "Observables (comma-separated), named as in the trajectory file: angular_momentum_1..3, gamma_1..3, "
                  "angular_velocity_1..3 (Cardan tops: cardan_angle_1..3, cardan_momentum_1..3, cos_cardan_angle_1..3, "
                  "sin_cardan_angle_1..3), or a complex pair A+iB of two of them (signed frequencies). Default: all "
                  "of the scene's kind")
      ->delimiter(',');
  sub->add_option("--terms", o->terms, "Terms per observable")->capture_default_str();
  sub->add_option("--window-order", o->window_order, "Order p of Laskar's window (error ~ T^-(2p+2))")
      ->capture_default_str();
  sub->add_option("--scheme", o->scheme,
                  "Scheme (default split-symmetric@kahan-li8; for a free body `exact` is the exact flow; Cardan tops: "
                  "a fixed-step T^3 scheme, default cardan-rk4)");
  sub->add_option("--dt", o->dt, "Step. Default: the scene's [run] dt");
  sub->add_option("--output-dt", o->output_dt, "Sample spacing D (a whole multiple of a fixed step). Default: --dt");
  sub->add_option("--tol", o->tol, "Tolerance of an adaptive scheme. Default: the scene's [run] tol, else 1e-10");
  sub->add_option("--state-file", o->state_file,
                  "Cardan tops: analyse each row of this HDF5 file (cardan_angles and cardan_momenta, or lgi "
                  "chaos-map's /orbits initial_cardan_angles and initial_cardan_momenta) instead of the scene's state");
  sub->add_option("--threads", o->threads, "OpenMP threads over the observables (Cardan: over the states) (default: all cores; at most 64 per core)")
      ->check(thread_count_check());
  sub->add_option("--out", o->out, "Output file (HDF5); the terms also as CSV beside it")->required();
  add_force_quiet_flags(*sub, *o, "Replace existing output files");
  sub->footer(exit_status_help);
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_frequencies(*o);
          },
          [o] { check_flags(*o); }};
}

}  // namespace lgi::experiments
