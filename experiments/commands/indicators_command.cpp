// lgi indicators --scene FILE [--t-end T] [--dt H | --scheme S] [--state-file F] [--spectrum] [--seed S]
//   [--rtol R] [--threads N] --out FILE.h5 [--force] [--quiet]
// The chaos indicators of chosen states (experiments/INDICATORS.md): the
// scene's initial state, or every row of a state file (angular_momentum and
// gamma, e.g. an `lgi equilibria` table), each integrated with its tangent
// flow (analysis/chaos_indicators.hpp): λ over [0, T] and over [T/2, T],
// MEGNO ⟨Y⟩, `converged`, and with --spectrum all six exponents.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "experiments/analysis/chaos_indicators.hpp"
#include "experiments/cli/thread_count.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/state_file.hpp"
#include "experiments/io/table_file.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

// The one scheme of the state with its tangent (integrators/tangent_flow.hpp).
constexpr const char* tangent_scheme = "rkmk4";

struct IndicatorsOptions {
  std::string scene, out, state_file, scheme;
  std::optional<double> t_end, dt;
  std::uint64_t seed = 0;
  double rtol = 0.05;
  int threads = 0;
  bool spectrum = false, force = false, quiet = false;
  std::string command_line;
};

std::string number(double x) { return format_general(x, 17); }

void check_flags(const IndicatorsOptions& o) {
  if (o.t_end && (!(*o.t_end > 0.0) || !std::isfinite(*o.t_end))) throw UsageError("--t-end: must be a positive number");
  if (o.dt && (!(*o.dt > 0.0) || !std::isfinite(*o.dt))) throw UsageError("--dt: must be a positive number");
  if (!o.scheme.empty() && o.scheme != tangent_scheme)
    throw UsageError("--scheme: '" + o.scheme + "' has no tangent flow; the indicators integrate the state with its "
                     "tangent vectors by rkmk4 (the only value)");
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
                                    const std::vector<StateIndicators>& results, bool spectrum) {
  std::vector<TableColumn> c = {{"index", 1, true}, {"lyapunov"}, {"lyapunov_last_half"}, {"megno"}, {"t_end"},
                                {"converged", 1, true}, {"angular_momentum", 3}, {"gamma", 3}};
  if (spectrum) c.push_back({"spectrum", 6});
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
    if (spectrum) c[8].real.insert(c[8].real.end(), r.spectrum.begin(), r.spectrum.end());
  }
  return c;
}

void print_rows(const std::vector<StateIndicators>& results, bool spectrum) {
  const std::size_t shown = std::min<std::size_t>(results.size(), 20);
  for (std::size_t i = 0; i < shown; ++i) {
    const StateIndicators& r = results[i];
    std::printf("index=%zu lyapunov=%.10g lyapunov_last_half=%.10g megno=%.6g converged=%s", i, r.lyapunov,
                r.lyapunov_last_half, r.megno, r.converged ? "yes" : "no");
    if (spectrum)
      std::printf(" spectrum=(%.6g, %.6g, %.6g, %.6g, %.6g, %.6g)", r.spectrum[0], r.spectrum[1], r.spectrum[2],
                  r.spectrum[3], r.spectrum[4], r.spectrum[5]);
    std::printf("\n");
  }
  if (shown < results.size()) std::printf("... %zu more rows in the file\n", results.size() - shown);
}

int run_indicators(const IndicatorsOptions& o) {
  check_flags(o);
  const system::Scene scene = read_scene(o.scene);
  refuse_cardan_scene(scene, "indicators");
  IndicatorSettings s;
  s.t_end = o.t_end ? *o.t_end : scene.t_end.value_or(0.0);
  if (!(s.t_end > 0.0)) throw UsageError("--t-end: missing, and the scene " + scene.file + " has no [run] t_end > 0");
  s.dt = o.dt ? *o.dt : scene.dt.value_or(0.0);
  if (!(s.dt > 0.0)) throw UsageError("--dt: missing, and the scene " + scene.file + " has no [run] dt");
  s.seed = o.seed, s.spectrum = o.spectrum, s.rtol = o.rtol;
  hdf5::check_output_target(o.out, o.force);
  std::string source;
  const std::vector<system::State> states = chosen_states(o, scene, source);
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  const auto start = std::chrono::steady_clock::now();
  std::vector<StateIndicators> results(states.size());
  const auto n = static_cast<std::int64_t>(states.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (std::int64_t i = 0; i < n; ++i)
    results[static_cast<std::size_t>(i)] = state_indicators(scene, states[static_cast<std::size_t>(i)], s, i);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::size_t failed = 0;
  for (const auto& r : results) failed += r.ok ? 0 : 1;
  const std::map<std::string, std::string> parameters = {
      {"subcommand", "indicators"}, {"command_line", o.command_line}, {"scene_file", scene.file},
      {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
      {"cxx_flags", build_info::cxx_flags}, {"t_end", number(s.t_end)}, {"dt", number(s.dt)},
      {"scheme", tangent_scheme}, {"seed", std::to_string(o.seed)}, {"rtol", number(o.rtol)},
      {"states", source}, {"state_file", o.state_file}, {"spectrum", o.spectrum ? "yes" : "no"},
      {"converged_rule", "|lyapunov_last_half - lyapunov| <= rtol * max(|lyapunov_last_half|, |lyapunov|)"},
      {"indicators", "RKMK4 on the state and its tangent (integrators/tangent_flow.hpp); experiments/INDICATORS.md"},
      {"threads", std::to_string(threads)}, {"wall_seconds", format_general(wall, 6)}};
  write_table_file(o.out, o.force, "indicators", columns_of(states, results, o.spectrum), parameters);
  if (failed > 0)
    std::cerr << "lgi: note: " << failed << " of " << results.size()
              << " states blew up (the state or the tangent is not finite): NaN indicators\n";
  if (o.quiet) return exit_ok;
  print_rows(results, o.spectrum);
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
      "and optionally the whole spectrum (experiments/INDICATORS.md)");
  sub->add_option("--scene", o->scene, "Scene file (an SO(3) scene: any torque terms)")->required();
  sub->add_option("--t-end", o->t_end, "Time span of each run (default: the scene's [run] t_end)");
  sub->add_option("--dt", o->dt, "Step of the state with its tangent (default: the scene's [run] dt)");
  sub->add_option("--scheme", o->scheme, "The scheme of the state with its tangent: rkmk4 (the only one)");
  sub->add_option("--state-file", o->state_file,
                  "States, one per row: HDF5 with a group of angular_momentum (n x 3) and gamma (n x 3), e.g. an "
                  "lgi equilibria file, or CSV with angular_momentum_1..3 and gamma_1..3 (default: the scene's "
                  "initial state)");
  sub->add_flag("--spectrum", o->spectrum, "Add /indicators/spectrum (n x 6): all six exponents (Gram-Schmidt)");
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
