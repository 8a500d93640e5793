// lgi indicators --scene FILE [--t-end T] [--dt H | --scheme S] [--state-file F] [--spectrum]
//   [--gali [--gali-samples N] [--gali-spacing log|linear]] [--seed S] [--rtol R] [--threads N]
//   --out FILE.h5 [--force] [--quiet]
// The chaos indicators of chosen states (experiments/INDICATORS.md): the
// scene's initial state, or every row of a state file (angular_momentum and
// gamma, e.g. an `lgi equilibria` table), each integrated with its tangent
// flow (analysis/chaos_indicators.hpp): λ over [0, T] and over [T/2, T],
// MEGNO ⟨Y⟩, `converged`, with --spectrum all six exponents, with --gali
// GALI_2 … GALI_6 (analysis/gali.hpp). A Cardan scene's initial state on
// T³ × ℝ³ is integrated with the torus tangent flow.
#include <omp.h>

#include <algorithm>
#include <span>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "experiments/analysis/chaos_indicators.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/thread_count.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/state_file.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "integrators/ensemble/ensemble.hpp"
#include "integrators/core/loop_support.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

// The one scheme of the state with its tangent: integrators/core/tangent_flow.hpp
// on SO(3), integrators/core/torus_tangent_flow.hpp on T³ × ℝ³.
constexpr const char* tangent_scheme = "rkmk4";
constexpr const char* torus_tangent_scheme = "cardan-rk4";

struct IndicatorsOptions {
  std::string scene, out, state_file, scheme;
  std::optional<double> t_end, dt;
  std::uint64_t seed = 0;
  double rtol = 0.05;
  int threads = 0, gali_samples = 100;
  std::string gali_spacing = "log";
  bool spectrum = false, gali = false, force = false, quiet = false;
  std::string command_line;
};


void check_flags(const IndicatorsOptions& o) {
  if (o.t_end && (!(*o.t_end > 0.0) || !std::isfinite(*o.t_end))) throw UsageError("--t-end: must be a positive number");
  if (o.dt && (!(*o.dt > 0.0) || !std::isfinite(*o.dt))) throw UsageError("--dt: must be a positive number");
  if (!o.scheme.empty() && o.scheme != tangent_scheme && o.scheme != torus_tangent_scheme)
    throw UsageError("--scheme: '" + o.scheme + "' has no tangent flow; the indicators integrate the state with its "
                     "tangent vectors by rkmk4 (SO(3) scenes) or cardan-rk4 (Cardan scenes)");
  if (o.gali_samples < 1 || o.gali_samples > 100000) throw UsageError("--gali-samples: must be in 1..100000");
  if (o.gali_spacing != "log" && o.gali_spacing != "linear")
    throw UsageError("--gali-spacing: '" + o.gali_spacing + "' is not log or linear");
  if (!(o.rtol > 0.0) || !std::isfinite(o.rtol)) throw UsageError("--rtol: must be a positive number");
  if (o.seed > static_cast<std::uint64_t>(INT64_MAX)) throw UsageError("--seed: at most 2^63 - 1");
}

/// The states to run: the scene's initial state, or the rows of --state-file.
std::vector<system::State> chosen_states(const IndicatorsOptions& o, const system::Scene& scene, std::string& source) {
  if (o.state_file.empty()) {
    source = "the scene's initial state";
    return {scene.initial};
  }
  const StateRows rows = read_state_file(o.state_file);
  source = o.state_file + " (" + rows.source + ")";
  int normalised = 0;
  std::vector<system::State> states = states_of(rows, o.state_file, normalised);
  if (normalised > 0)
    std::cerr << "lgi: note: " << o.state_file << ": " << normalised
              << " rows with |gamma| differing from 1 by more than 1e-12, normalised\n";
  return states;
}

std::vector<TableColumn> columns_of(const std::vector<system::State>& states,
                                    const std::vector<StateIndicators>& results, const IndicatorSettings& s) {
  std::vector<TableColumn> c = {{"index", 1, true}, {"lyapunov"}, {"lyapunov_last_half"}, {"megno"}, {"t_end"},
                                {"converged", 1, true}, {"angular_momentum", 3}, {"gamma", 3}};
  if (s.spectrum) c.push_back({"spectrum", 6});
  for (std::size_t i = 0; i < results.size(); ++i) {
    const StateIndicators& r = results[i];
    c[0].whole.push_back(static_cast<std::int64_t>(i));
    c[1].real.push_back(r.lyapunov);
    c[2].real.push_back(r.lyapunov_last_half);
    c[3].real.push_back(r.megno);
    c[4].real.push_back(r.t_end);
    c[5].whole.push_back(r.converged ? 1 : 0);
    const lie::Vec3 gamma = states[i].R.transpose() * lie::Vec3::UnitZ();
    c[6].real.insert(c[6].real.end(), states[i].Pi.data(), states[i].Pi.data() + 3);
    c[7].real.insert(c[7].real.end(), gamma.data(), gamma.data() + 3);
    if (s.spectrum) c[8].real.insert(c[8].real.end(), r.spectrum.begin(), r.spectrum.end());
  }
  if (s.gali)  // log10 GALI_k at T: the last sample of each curve
    for (int k = 2; k <= 6; ++k) {
      TableColumn g{"log10_gali_" + std::to_string(k)};
      for (const auto& r : results)  // a state a signal kept from starting has no curve
        g.real.push_back(r.gali.log10_gali.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                   : r.gali.log10_gali.back()[static_cast<std::size_t>(k - 2)]);
      c.push_back(std::move(g));
    }
  return c;
}

/// A Cardan scene's state on T³ × ℝ³ as columns: the angles and their momenta.
void add_cardan_columns(std::vector<TableColumn>& c, const system::TorusState& x, std::size_t rows) {
  TableColumn q{"cardan_angles", 3}, p{"cardan_momenta", 3};
  for (std::size_t i = 0; i < rows; ++i) {
    q.real.insert(q.real.end(), x.q.data(), x.q.data() + 3);
    p.real.insert(p.real.end(), x.p.data(), x.p.data() + 3);
  }
  c.push_back(std::move(q));
  c.push_back(std::move(p));
}

/// /gali: one row per (state, sample time), the states in order and each one's times increasing.
TableGroup gali_group(const std::vector<StateIndicators>& results, const IndicatorSettings& s) {
  TableGroup g{"gali", {{"index", 1, true}, {"t"}, {"log10_gali", gali_orders}}, {}};
  for (std::size_t i = 0; i < results.size(); ++i) {
    const GaliCurves& c = results[i].gali;
    for (std::size_t j = 0; j < c.t.size(); ++j) {
      g.columns[0].whole.push_back(static_cast<std::int64_t>(i));
      g.columns[1].real.push_back(c.t[j]);
      g.columns[2].real.insert(g.columns[2].real.end(), c.log10_gali[j].begin(), c.log10_gali[j].end());
    }
  }
  g.attributes = {{"k", "2 3 4 5 6 (the columns of log10_gali)"},
                  {"samples", std::to_string(s.gali_sampling.samples)},
                  {"spacing", s.gali_sampling.log_spacing ? "log" : "linear"},
                  {"times_per_state", std::to_string(results.empty() ? 0 : results[0].gali.t.size())},
                  {"method", "Skokos, Bountis & Antonopoulos (2007, 2008): six deviation vectors normalised after "
                             "every step; GALI_k = product of the singular values of the first k; experiments/INDICATORS.md"}};
  return g;
}

void print_rows(const std::vector<StateIndicators>& results, const IndicatorSettings& s) {
  const std::size_t shown = std::min<std::size_t>(results.size(), 20);
  for (std::size_t i = 0; i < shown; ++i) {
    const StateIndicators& r = results[i];
    std::printf("index=%zu lyapunov=%.10g lyapunov_last_half=%.10g megno=%.6g converged=%s", i, r.lyapunov,
                r.lyapunov_last_half, r.megno, r.converged ? "yes" : "no");
    if (s.spectrum)
      std::printf(" spectrum=(%.6g, %.6g, %.6g, %.6g, %.6g, %.6g)", r.spectrum[0], r.spectrum[1], r.spectrum[2],
                  r.spectrum[3], r.spectrum[4], r.spectrum[5]);
    if (s.gali) {
      const GaliValues& g = r.gali.log10_gali.back();
      std::printf(" log10_gali_2..6=(%.4g, %.4g, %.4g, %.4g, %.4g)", g[0], g[1], g[2], g[3], g[4]);
    }
    std::printf("\n");
  }
  if (shown < results.size()) std::printf("... %zu more rows in the file\n", results.size() - shown);
}

/// The run's settings from the flags and the scene's [run] defaults.
IndicatorSettings settings_of(const IndicatorsOptions& o, const system::Scene& scene) {
  const bool cardan = scene.suspension.has_value();
  if (cardan && !o.state_file.empty())
    throw UsageError("--state-file: " + scene.file + " is a Cardan top (T^3 x R^3); lgi indicators takes its "
                     "[initial] state only");
  if (!o.scheme.empty() && o.scheme != (cardan ? torus_tangent_scheme : tangent_scheme))
    throw UsageError("--scheme: " + o.scheme + " does not integrate " + scene.file + "; its tangent flow is " +
                     (cardan ? torus_tangent_scheme : tangent_scheme));
  IndicatorSettings s;
  s.t_end = o.t_end ? *o.t_end : scene.t_end.value_or(0.0);
  if (!(s.t_end > 0.0)) throw UsageError("--t-end: missing, and the scene " + scene.file + " has no [run] t_end > 0");
  s.dt = o.dt ? *o.dt : scene.dt.value_or(0.0);
  if (!(s.dt > 0.0)) throw UsageError("--dt: missing, and the scene " + scene.file + " has no [run] dt");
  if (const std::string why = integrators::fixed_step_grid_problem(0.0, s.t_end, s.dt); !why.empty())
    throw UsageError("--dt: " + why);
  s.seed = o.seed, s.spectrum = o.spectrum, s.rtol = o.rtol, s.gali = o.gali;
  s.gali_sampling = {o.gali_samples, o.gali_spacing == "log"};
  return s;
}

int run_indicators(const IndicatorsOptions& o) {
  check_flags(o);
  const system::Scene scene = read_scene(o.scene);
  const bool cardan = scene.suspension.has_value();
  const IndicatorSettings s = settings_of(o, scene);
  hdf5::check_output_target(o.out, o.force);
  std::string source = "the scene's initial state (cardan_angles, cardan_rates)";
  const std::vector<system::State> states = cardan ? std::vector<system::State>{scene.initial}
                                                   : chosen_states(o, scene, source);
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  // Ctrl-C / SIGTERM: the tangent flows stop within a few steps (they read the flag), no state starts after
  // it, and what was computed goes to <out>.partial; a state the signal cut short or kept from starting has
  // NaN indicators and t_end 0 (its run is not a measurement).
  const InterruptGuard interrupt_guard;
  const auto start = std::chrono::steady_clock::now();
  StateIndicators not_run;
  not_run.lyapunov = not_run.lyapunov_last_half = not_run.megno = std::numeric_limits<double>::quiet_NaN();
  not_run.spectrum.fill(std::numeric_limits<double>::quiet_NaN());
  std::vector<StateIndicators> results(states.size(), not_run);
  // A task is up to max_lanes states, whose λ and ⟨Y⟩ run together in SIMD lanes (the same bits; docs/ensemble.md).
  constexpr std::int64_t batch = integrators::ensemble::max_lanes;
  const auto n = static_cast<std::int64_t>(states.size());
  const std::optional<integrators::ensemble::Isa> isa = integrators::ensemble::sweep_isa();
  // Progress on stderr (cli/sweep_progress.hpp; issue 50, item 8): in place on a terminal, else every 10 s.
  SweepProgress progress(o.quiet, n, 0, "indicators", "states");
  std::int64_t finished = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (std::int64_t first = 0; first < n; first += batch) {
    if (interrupt_requested.load(std::memory_order_relaxed)) continue;
    const auto u = static_cast<std::size_t>(first), m = static_cast<std::size_t>(std::min(batch, n - first));
    std::vector<StateIndicators> part(m, not_run);
    if (cardan) part[0] = cardan_state_indicators(scene, scene.cardan_initial, s, first);
    else state_indicators(scene, std::span(states).subspan(u, m), s, first, isa, std::span(part));
    if (interrupt_requested.load()) continue;  // maybe cut short: neither kept nor counted
    std::copy(part.begin(), part.end(), results.begin() + first);
#pragma omp critical(indicators_progress)
    progress.update(finished += static_cast<std::int64_t>(m), 0);
  }
  progress.finish();
  const bool interrupted = interrupt_signal() != 0;
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::size_t failed = 0;
  for (const auto& r : results) failed += r.ok ? 0 : 1;
  const std::map<std::string, std::string> parameters = {
      {"subcommand", "indicators"}, {"command_line", o.command_line}, {"scene_file", scene.file},
      {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
      {"cxx_flags", build_info::cxx_flags}, {"t_end", format_exact(s.t_end)}, {"dt", format_exact(s.dt)},
      {"scheme", cardan ? torus_tangent_scheme : tangent_scheme}, {"seed", std::to_string(o.seed)},
      {"rtol", format_exact(o.rtol)}, {"states", source}, {"state_file", o.state_file},
      {"spectrum", o.spectrum ? "yes" : "no"}, {"gali", o.gali ? "yes" : "no"},
      {"gali_samples", std::to_string(o.gali_samples)}, {"gali_spacing", o.gali_spacing},
      {"converged_rule", "|lyapunov_last_half - lyapunov| <= rtol * max(|lyapunov_last_half|, |lyapunov|)"},
      {"indicators", cardan ? "RK4 on the Cardan state and its tangent (integrators/ensemble/cardan_tangent_kernel.hpp); "
                              "experiments/INDICATORS.md"
                            : "RKMK4 on the state and its tangent (integrators/core/tangent_flow.hpp, "
                              "integrators/ensemble/tangent_ensemble.hpp); experiments/INDICATORS.md"},
      {"threads", std::to_string(threads)}, {"wall_seconds", format_general(wall, 6)},
      {"status", interrupted ? "interrupted by signal" : "complete"}};
  std::vector<TableColumn> columns = columns_of(states, results, s);
  if (cardan) add_cardan_columns(columns, scene.cardan_initial, states.size());
  std::vector<TableGroup> groups;
  if (s.gali) groups.push_back(gali_group(results, s));
  if (interrupted) {  // the HDF5 file alone, as <out>.partial (no CSV): an incomplete table
    const std::string partial = o.out + ".partial";
    groups.insert(groups.begin(), TableGroup{"indicators", columns, {}});
    write_groups_file(partial, true, groups, parameters);
    std::cerr << "lgi: indicators interrupted by signal; the states so far (each row's t_end says how far it got) "
                 "are kept in "
              << partial << '\n';
    return interrupted_exit_status();
  }
  write_table_file(o.out, o.force, "indicators", columns, parameters, groups);
  if (failed > 0)
    std::cerr << "lgi: note: " << failed << " of " << results.size()
              << " states blew up (the state or the tangent is not finite): NaN indicators\n";
  if (o.quiet) return exit_ok;
  print_rows(results, s);
  std::cout << results.size() << " states to t = " << format_general(s.t_end, 10) << " with dt = "
            << format_general(s.dt, 10) << "; "
            << format_general(wall, 3) << " s wall on " << threads << " threads; wrote " << o.out << '\n';
  return exit_ok;
}

}  // namespace

Subcommand add_indicators_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<IndicatorsOptions>();
  auto* sub = app.add_subcommand(
      "indicators",
      "Chaos indicators of chosen states: the largest Lyapunov exponent over the run and its second half, MEGNO, "
      "optionally the whole spectrum and GALI_2..6; SO(3) and Cardan scenes (experiments/INDICATORS.md)");
  sub->add_option("--scene", o->scene, "Scene file (an SO(3) scene with any torque terms, or a Cardan top)")->required();
  sub->add_option("--t-end", o->t_end, "Time span of each run (default: the scene's [run] t_end)");
  sub->add_option("--dt", o->dt, "Step of the state with its tangent (default: the scene's [run] dt)");
  sub->add_option("--scheme", o->scheme, "The scheme of the state with its tangent: rkmk4 (SO(3) scenes) or "
                                         "cardan-rk4 (Cardan scenes), the only ones");
  sub->add_option("--state-file", o->state_file,
                  "States, one per row: HDF5 with a group of angular_momentum (n x 3) and gamma (n x 3), e.g. an "
                  "lgi equilibria file, or CSV with angular_momentum_1..3 and gamma_1..3 (default: the scene's "
                  "initial state)");
  sub->add_flag("--spectrum", o->spectrum, "Add /indicators/spectrum (n x 6): all six exponents (Gram-Schmidt)");
  sub->add_flag("--gali", o->gali, "Add GALI_2..GALI_6: /indicators/log10_gali_2..6 at t_end and the curves in /gali");
  sub->add_option("--gali-samples", o->gali_samples, "Sample times of the GALI curves (at most; each at a step's end)")
      ->capture_default_str();
  sub->add_option("--gali-spacing", o->gali_spacing, "Sample times evenly in log t on [dt, T] (log) or in t (linear)")
      ->capture_default_str();
  sub->add_option("--seed", o->seed, "Seed of the tangent vectors (with each state's index)")->capture_default_str();
  sub->add_option("--rtol", o->rtol, "converged = 1 where the exponents over [T/2, T] and [0, T] agree to this, "
                                     "relative")->capture_default_str();
  sub->add_option("--threads", o->threads, "OpenMP threads (default: all cores; at most 64 per core)")->check(thread_count_check());
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV beside it")->required();
  add_force_quiet_flags(*sub, *o, "Replace existing output files");
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_indicators(*o);
          },
          [o] { check_flags(*o); }};
}

}  // namespace lgi::experiments
