// lgi frequencies --scene FILE --t-end T [--observable NAME[,NAME...]] [--terms K] [--window-order P]
//   [--scheme S] [--dt H] [--output-dt D] [--tol TOL] [--threads N] --out FILE.h5 [--force] [--quiet]
// Laskar's frequency analysis (NAFF) of chosen observables along the scene's
// trajectory (experiments/FREQUENCIES.md, docs/frequency_analysis.md): the
// run samples them at t0 + k D (analysis/frequency/observable_series.hpp),
// NAFF gives K terms each (naff.hpp), and the two halves of the run the
// diffusion index (frequency_diffusion.hpp).
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

#include "experiments/analysis/frequency/observable_frequencies.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/thread_count.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "integrators/system/model.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

namespace fq = frequency;

struct FrequenciesOptions {
  std::string scene, out, scheme = "split-symmetric@kahan-li8";
  std::optional<double> t_end, dt, output_dt, tol;
  std::vector<std::string> observables;
  int terms = 5, window_order = 1, threads = 0;
  bool force = false, quiet = false;
  std::string command_line;
};

std::string number(double x) { return format_general(x, 17); }
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

std::vector<TableColumn> term_columns(const std::vector<fq::ObservableFrequencies>& records) {
  std::vector<TableColumn> c = {{"observable"}, {"term", 1, true}, {"frequency"}, {"amplitude"},
                                {"phase"},      {"period"},         {"diffusion"}};
  c[0].is_text = true;
  for (const auto& r : records)
    for (std::size_t k = 0; k < r.terms.terms.size(); ++k) {
      const fq::NaffTerm& t = r.terms.terms[k];
      c[0].text.push_back(r.observable);
      c[1].whole.push_back(static_cast<std::int64_t>(k));
      c[2].real.push_back(t.frequency);
      c[3].real.push_back(t.amplitude);
      c[4].real.push_back(t.phase);
      c[5].real.push_back(2.0 * std::numbers::pi / std::abs(t.frequency));
      c[6].real.push_back(r.diffusion.log10_relative_change);  // the observable's, on each of its rows
    }
  return c;
}

TableGroup diffusion_group(const std::vector<fq::ObservableFrequencies>& records) {
  TableGroup g{"frequency_diffusion"};
  g.columns = {{"observable"}, {"frequency"}, {"frequency_first_half"}, {"frequency_second_half"},
               {"relative_change"}, {"log10_relative_change"}, {"mean"}};
  g.columns[0].is_text = true;
  for (const auto& r : records) {
    g.columns[0].text.push_back(r.observable);
    g.columns[1].real.push_back(r.terms.terms.empty() ? std::nan("") : r.terms.terms[0].frequency);
    g.columns[2].real.push_back(r.diffusion.first_half);
    g.columns[3].real.push_back(r.diffusion.second_half);
    g.columns[4].real.push_back(r.diffusion.relative_change);
    g.columns[5].real.push_back(r.diffusion.log10_relative_change);
    g.columns[6].real.push_back(r.terms.mean.real());
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

int run_frequencies(const FrequenciesOptions& o) {
  check_flags(o);
  const system::Scene scene = read_scene(o.scene);
  if (scene.suspension)
    throw UsageError("--scene: " + scene.file + " is a Cardan top; lgi frequencies analyses SO(3) scenes only");
  const integrators::SchemeInfo& scheme = scheme_by_name(o.scheme, "--scheme");
  const fq::SamplingSettings s = sampling(o, scene, scheme);
  hdf5::check_output_target(o.out, o.force);
  const std::vector<std::string> names = o.observables.empty() ? fq::observable_names() : o.observables;
  const auto start = std::chrono::steady_clock::now();
  fq::SampledRun run;
  {
    const InterruptGuard interrupt_guard;
    run = fq::sample_observables(scene, scheme, s, fq::components_of(names), &interrupt_requested);
  }
  if (!run.stats.ok) {
    std::cerr << "lgi: " << scheme.name << " on " << scene.file << ": " << run.stats.status << '\n';
    return run.stats.interrupted ? interrupted_exit_status() : exit_run_failed;
  }
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  const auto records = fq::observable_frequencies(run, names, {o.terms, o.window_order}, threads);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::map<std::string, std::string> parameters = {
      {"subcommand", "frequencies"}, {"command_line", o.command_line}, {"scene_file", scene.file},
      {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
      {"cxx_flags", build_info::cxx_flags}, {"scheme", scheme.name}, {"t_end", number(s.t_end)},
      {"dt", number(s.dt)}, {"output_dt", number(s.output_dt)}, {"samples", std::to_string(run.series[0].size())},
      {"terms", std::to_string(o.terms)}, {"window_order", std::to_string(o.window_order)},
      {"method", "NAFF (Laskar 1990, 1993): window chi_p, FFT peak, Brent, zero of the derivative, Gram-Schmidt; "
                 "real signals as c + sum A cos(w (t - t0) + phi), w > 0; docs/frequency_analysis.md"},
      {"threads", std::to_string(threads)}, {"wall_seconds", format_general(wall, 6)}};
  write_table_file(o.out, o.force, "frequencies", term_columns(records), parameters, {diffusion_group(records)});
  if (o.quiet) return exit_ok;
  print_records(records);
  std::cout << run.series[0].size() << " samples to t = " << format_general(s.t_end, 10) << "; wrote " << o.out
            << '\n';
  return exit_ok;
}

}  // namespace

Subcommand add_frequencies_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<FrequenciesOptions>();
  auto* sub = app.add_subcommand(
      "frequencies",
      "Laskar's frequency analysis (NAFF) of observables along the scene's trajectory, with the diffusion index of "
      "the run's two halves (experiments/FREQUENCIES.md)");
  sub->add_option("--scene", o->scene, "Scene file (TOML), an SO(3) scene")->required();
  sub->add_option("--t-end", o->t_end, "Length of the run T")->required();
  sub->add_option("--observable", o->observables,
                  "Observables (comma-separated), named as in the trajectory file: angular_momentum_1..3, gamma_1..3, "
                  "angular_velocity_1..3, or a complex pair A+iB of two of them (signed frequencies). Default: the nine")
      ->delimiter(',');
  sub->add_option("--terms", o->terms, "Terms per observable")->capture_default_str();
  sub->add_option("--window-order", o->window_order, "Order p of Laskar's window (error ~ T^-(2p+2))")
      ->capture_default_str();
  sub->add_option("--scheme", o->scheme, "Scheme (for a free body, `exact` is the exact flow)")->capture_default_str();
  sub->add_option("--dt", o->dt, "Step. Default: the scene's [run] dt");
  sub->add_option("--output-dt", o->output_dt, "Sample spacing D (a whole multiple of a fixed step). Default: --dt");
  sub->add_option("--tol", o->tol, "Tolerance of an adaptive scheme. Default: the scene's [run] tol, else 1e-10");
  sub->add_option("--threads", o->threads, "OpenMP threads over the observables (default: all cores; at most 64 per core)")
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
