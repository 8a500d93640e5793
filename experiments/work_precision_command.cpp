// lgi work-precision: global error at t_end against a reference, and CPU
// time (min and median over N timed runs that write nothing), for each scheme
// and each step (fixed-step schemes: --dt) or tolerance (adaptive: --tol).
// Layout of the result file: experiments/RESULTS.md.
//
// Reference (/reference in the file):
//   free body      the exact flow (system::FreeBodyExactFlow) at t_end;
//                  kind "exact". Its estimated_error is the conditioning
//                  floor of the problem (exact_conditioning_floor): the
//                  spread of exact flows from initial states perturbed at
//                  round-off, and the flow's own consistency under
//                  splitting [0, T] in two. Near a separatrix it reaches
//                  1e-7; rows under it are not measurements.
//   any other      a converged run of rkmk-dp54 (adaptive RKMK of order 5;
//                  supports every model: torques, damping, drives) at tol 1e-14;
//                  its error is estimated by the distance (the global error
//                  measure of docs/conventions.md §7) to a run at tol 1e-13. That is
//                  about the error of the coarser run: on the shipped scenes
//                  the DP5(4) error is proportional to tol down to 1e-14 or
//                  1e-15 (distances 1e-12 -> 1e-13 -> 1e-14 shrink tenfold),
//                  so the estimate exceeds the reference's own error about
//                  tenfold. If a run fails (step size collapse), both
//                  tolerances are relaxed tenfold, up to 1e-12 / 1e-11.
// A row whose error is below its floor (the reference's estimated error, or
// for an exact reference the round-off its steps accumulate through the
// problem's amplification, row_floor) is not a measurement: its error columns
// hold NaN, below_reference_floor = 1, and error_floor says where the floor is.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "experiments/commands.hpp"
#include "experiments/exit_status.hpp"
#include "experiments/results_file.hpp"
#include "experiments/run_parameters.hpp"
#include "experiments/scene_reader.hpp"
#include "experiments/scheme_lookup.hpp"
#include "experiments/step_settings.hpp"
#include "integrators/registry.hpp"
#include "integrators/system/free_body_exact.hpp"
#include "integrators/system/invariants.hpp"
#include "lie/quaternion.hpp"

namespace lgi::experiments {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

struct WorkPrecisionOptions {
  std::string scene;
  std::vector<std::string> schemes;
  std::vector<double> dt;
  std::vector<double> tol;
  std::optional<double> t_end;
  int repeat = 5;
  std::string out;
  bool force = false;
  bool quiet = false;
  std::string command_line;
};

/// Keeps only the latest state; the registry's runs call it at step 0 and at
/// the final step (save_every is larger than any run).
class FinalStateObserver final : public integrators::Observer {
 public:
  void observe(std::int64_t step, double t, const system::State& s) override {
    last_step = step;
    last_time = t;
    last = s;
  }
  std::int64_t last_step = -1;
  double last_time = 0.0;
  system::State last{};
};

struct GlobalError {
  double attitude = nan, momentum = nan, max = nan;
};

/// docs/conventions.md §7: geodesic angle, relative momentum error, the larger.
GlobalError global_error(const system::State& s, const system::State& ref) {
  GlobalError e;
  if (!s.R.allFinite() || !s.Pi.allFinite()) return e;
  e.attitude = lie::geodesic_distance(ref.R, s.R);
  const double pn = ref.Pi.norm();
  const double d = (s.Pi - ref.Pi).norm();
  e.momentum = pn > 0.0 ? d / pn : d;
  e.max = std::max(e.attitude, e.momentum);
  return e;
}

struct RunResult {
  integrators::RunStats stats;
  system::State final{};
  bool threw = false;
};

RunResult run_once(const integrators::SchemeInfo& scheme, const system::AnyModel& model, const system::State& initial,
                   const integrators::RunConfig& cfg) {
  RunResult r;
  r.final = initial;
  FinalStateObserver observer;
  try {
    r.stats = scheme.run(model, r.final, cfg, observer);
  } catch (const std::exception& e) {
    r.threw = true;
    r.stats.ok = false;
    r.stats.status = e.what();
  }
  return r;
}

integrators::RunConfig make_config(double t_end, std::optional<double> dt, std::optional<double> tol) {
  integrators::RunConfig cfg;
  cfg.t0 = 0.0;
  cfg.t_end = t_end;
  cfg.dt = dt.value_or(0.0);
  cfg.tol = tol.value_or(0.0);
  cfg.save_every = std::numeric_limits<std::int64_t>::max();  // observe the initial and the final state only
  return cfg;
}

std::string format_g(double x, int precision = 3) {
  if (std::isnan(x)) return "nan";
  std::ostringstream s;
  s.precision(precision);
  s << x;
  return s.str();
}

std::string format_e(double x) {
  if (std::isnan(x)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3e", x);
  return buf;
}

struct Reference {
  std::string kind;    // "exact" or "converged"
  std::string scheme;  // "exact" or the scheme's name
  double tol = nan;
  double comparison_tol = nan;
  double estimated_error = 0.0;
  double amplification = 0.0;  // exact references: κ of exact_conditioning_floor
  std::int64_t steps = -1;
  double cpu_seconds = nan;
  system::State state{};
};

/// The conditioning floor of an exact reference: the larger of
///  - the spread at t_end of exact flows from initial states perturbed at
///    round-off (δ = 1e-15 relative, R → R exp(δ e_j), Π → Π + δ|Π| e_j), and
///  - the flow's own consistency, |E_T(x0) − E_{T−s}(E_s(x0))| for s = T/3,
///    T/2: the evaluation error of the elliptic functions, which near a
///    separatrix (modulus near 1) exceeds the perturbation spread by far.
struct ExactFloor {
  double floor = 0.0;          // the reference's estimated error
  double amplification = 0.0;  // κ: spread at t_end per unit relative perturbation of the initial state
};

ExactFloor exact_conditioning_floor(const system::Inertia& inertia, const system::State& initial,
                                   const system::State& exact_end, double t_end) {
  constexpr double delta = 1e-15;
  double floor = 0.0;
  auto widen = [&](double d) {
    if (!(d <= floor)) floor = d;  // NaN propagates
  };
  for (int j = 0; j < 6; ++j) {
    system::State x = initial;
    if (j < 3) x.R = initial.R * lie::exp_so3(delta * lie::Vec3::Unit(j));
    else x.Pi += delta * initial.Pi.norm() * lie::Vec3::Unit(j - 3);
    widen(global_error(system::FreeBodyExactFlow(inertia, x).at(t_end), exact_end).max);
  }
  const double amplification = floor / delta;
  const system::FreeBodyExactFlow from_initial(inertia, initial);
  for (const double s : {t_end / 3.0, t_end / 2.0}) {
    const system::State midway = from_initial.at(s);
    widen(global_error(system::FreeBodyExactFlow(inertia, midway).at(t_end - s), exact_end).max);
  }
  return {floor, amplification};
}

/// The floor of one row: the reference's, or the round-off a run of `steps`
/// steps accumulates (one unit round-off a step, worst case, amplified by κ,
/// with a safety factor of 4), whichever is larger. Near a separatrix the
/// second dominates: rkmk4 on a T-handle over 50 s bottoms out near 1e-7
/// at 2e4 steps, as κ u N predicts.
double row_floor(double reference_error, double amplification, std::int64_t steps) {
  constexpr double unit_roundoff = 0x1p-53;
  return std::max(reference_error, 4.0 * amplification * unit_roundoff * static_cast<double>(steps));
}

Reference compute_reference(const system::Scene& scene, const system::AnyModel& model, double t_end) {
  Reference ref;
  if (const auto* free = std::get_if<system::FreeBody>(&model)) {
    ref.kind = "exact";
    ref.scheme = "exact";
    const system::FreeBodyExactFlow flow(free->inertia, scene.initial);
    ref.state = flow.at(t_end);
    const ExactFloor floor = exact_conditioning_floor(free->inertia, scene.initial, ref.state, t_end);
    ref.estimated_error = floor.floor;
    ref.amplification = floor.amplification;
    ref.steps = 0;
    return ref;
  }
  const integrators::SchemeInfo* dp54 = integrators::find_scheme("rkmk-dp54");
  if (!dp54) throw RunError("work-precision: the reference scheme rkmk-dp54 is not registered");
  std::string last_failure;
  for (const double tol : {1e-14, 1e-13, 1e-12}) {
    const RunResult fine = run_once(*dp54, model, scene.initial, make_config(t_end, std::nullopt, tol));
    if (!fine.stats.ok) {
      last_failure = "at tol " + format_g(tol) + ": " + fine.stats.status;
      continue;
    }
    const RunResult coarse = run_once(*dp54, model, scene.initial, make_config(t_end, std::nullopt, 10.0 * tol));
    if (!coarse.stats.ok) {
      last_failure = "at tol " + format_g(10.0 * tol) + ": " + coarse.stats.status;
      continue;
    }
    ref.kind = "converged";
    ref.scheme = dp54->name;
    ref.tol = tol;
    ref.comparison_tol = 10.0 * tol;
    ref.estimated_error = global_error(coarse.final, fine.final).max;
    ref.steps = fine.stats.steps;
    ref.cpu_seconds = fine.stats.cpu_seconds;
    ref.state = fine.final;
    if (!std::isfinite(ref.estimated_error)) {
      last_failure = "non-finite error estimate";
      continue;
    }
    return ref;
  }
  throw RunError("work-precision: no converged reference for " + scene.file + " (rkmk-dp54 " + last_failure + ")");
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}

/// One row to run: a scheme with a step or a tolerance.
struct Job {
  const integrators::SchemeInfo* scheme = nullptr;
  std::optional<double> dt, tol;
};

std::vector<Job> plan(const WorkPrecisionOptions& o) {
  if (o.schemes.empty()) throw UsageError("--schemes: empty list (give A,B,...; lgi schemes lists them)");
  std::vector<const integrators::SchemeInfo*> schemes;
  std::set<std::string> seen;
  for (const auto& name : o.schemes) {
    if (name.empty()) throw UsageError("--schemes: empty scheme name in the list");
    const integrators::SchemeInfo* s = &scheme_by_name(name, "--schemes");
    if (!seen.insert(name).second) throw UsageError("--schemes: scheme '" + name + "' given twice");
    schemes.push_back(s);
  }
  for (double h : o.dt)
    if (!(h > 0.0 && std::isfinite(h))) throw UsageError("--dt: every step must be a finite number > 0, got " + format_g(h, 6));
  for (double t : o.tol)
    if (!(t > 0.0 && std::isfinite(t)))
      throw UsageError("--tol: every tolerance must be a finite number > 0, got " + format_g(t, 6));
  if (o.repeat < 1) throw UsageError("--repeat: must be >= 1");

  std::vector<Job> jobs;
  for (const auto* s : schemes) {
    if (s->properties.adaptive) {
      if (o.tol.empty())
        throw UsageError("--tol: scheme '" + s->name +
                         "' is adaptive and needs a list of tolerances: give --tol A,B,... or [run] tol in the scene");
      for (double t : o.tol) jobs.push_back({s, std::nullopt, t});
    } else {
      if (o.dt.empty())
        throw UsageError("--dt: scheme '" + s->name +
                         "' is fixed-step and needs a list of steps: give --dt A,B,... or [run] dt in the scene");
      for (double h : o.dt) jobs.push_back({s, h, std::nullopt});
    }
  }
  return jobs;
}

int work_precision(const WorkPrecisionOptions& o) {
  const system::Scene scene = read_scene(o.scene);
  // The command line, then the scene's [run] (step_settings.hpp).
  WorkPrecisionOptions resolved = o;
  resolved.dt = default_step_list(o.dt, scene.dt);
  resolved.tol = default_tolerance_list(o.tol, scene.tol);
  const std::vector<Job> jobs = plan(resolved);
  if (!o.quiet) {  // about the flags as given, not the scene's defaults
    const bool any_fixed = std::any_of(jobs.begin(), jobs.end(), [](const Job& j) { return j.dt.has_value(); });
    const bool any_adaptive = std::any_of(jobs.begin(), jobs.end(), [](const Job& j) { return j.tol.has_value(); });
    if (!o.dt.empty() && !any_fixed) std::cerr << "lgi: warning: --dt ignored: no fixed-step scheme in --schemes\n";
    if (!o.tol.empty() && !any_adaptive) std::cerr << "lgi: warning: --tol ignored: no adaptive scheme in --schemes\n";
  }
  const double t_end = resolve_t_end(o.t_end, scene, /*allow_zero=*/false);
  const system::AnyModel model = system::make_model(scene);
  const system::SceneInvariants invariants(scene, model);
  const bool progress = !o.quiet && ::isatty(STDERR_FILENO) == 1;

  // Columns (RESULTS.md).
  std::vector<Column> columns = {
      {"scheme", ColumnType::text, ""},
      {"dt", ColumnType::real, "s"},
      {"tol", ColumnType::real, ""},
      {"steps", ColumnType::integer, ""},
      {"rejected_steps", ColumnType::integer, ""},
      {"rhs_evaluations", ColumnType::integer, ""},
      {"error_attitude", ColumnType::real, "rad"},
      {"error_momentum", ColumnType::real, ""},
      {"error", ColumnType::real, ""},
  };
  std::vector<std::string> invariant_columns;
  if (invariants.energy_conserved()) invariant_columns.push_back("error_energy");
  for (const auto& n : invariants.scalar_names()) invariant_columns.push_back("error_" + n);
  if (invariants.free_body()) invariant_columns.push_back("error_angular_momentum_space");
  invariant_columns.push_back("error_orthogonality");
  for (const auto& c : invariant_columns) columns.push_back({c, ColumnType::real, ""});
  for (const char* c : {"cpu_seconds_min", "cpu_seconds_median"}) columns.push_back({c, ColumnType::real, "s"});
  columns.push_back({"repeats", ColumnType::integer, ""});
  columns.push_back({"status", ColumnType::text, ""});
  columns.push_back({"below_reference_floor", ColumnType::integer, ""});
  columns.push_back({"error_floor", ColumnType::real, ""});

  ResultsFile file(o.out, o.force, columns);

  ResultAttributes params = scene_parameters(scene);
  params.text["subcommand"] = "work-precision";
  params.text["schemes"] = join(o.schemes, ",");
  params.text["command_line"] = o.command_line;
  params.number["t_end"] = t_end;
  params.integer["repeat"] = o.repeat;
  if (!resolved.dt.empty()) params.number_array["dt"] = resolved.dt;
  if (!resolved.tol.empty()) params.number_array["tol"] = resolved.tol;
  file.write_parameters(params);

  const double cpu0 = integrators::detail::cpu_now();
  if (progress) std::cerr << "\rwork-precision: reference..." << std::flush;
  Reference ref;
  try {
    ref = compute_reference(scene, model, t_end);
  } catch (const RunError& e) {
    ResultAttributes diag;
    diag.text["status"] = e.what();
    file.abandon(diag);
    if (progress) std::cerr << '\n';
    std::cerr << "lgi: " << e.what() << "; partial results kept in " << file.partial_path() << '\n';
    return exit_run_failed;
  }
  {
    ResultAttributes a;
    a.text["kind"] = ref.kind;
    a.text["scheme"] = ref.scheme;
    a.number["estimated_error"] = ref.estimated_error;
    if (ref.kind == "exact") a.number["amplification"] = ref.amplification;
    a.number["t_end"] = t_end;
    if (ref.kind == "converged") {
      a.number["tol"] = ref.tol;
      a.number["comparison_tol"] = ref.comparison_tol;
      a.integer["steps"] = ref.steps;
      a.number["cpu_seconds"] = ref.cpu_seconds;
    }
    const Eigen::Quaterniond q = lie::quat_from_matrix(ref.state.R);
    a.number_array["orientation"] = {q.w(), q.x(), q.y(), q.z()};
    a.number_array["angular_momentum_body"] = {ref.state.Pi.x(), ref.state.Pi.y(), ref.state.Pi.z()};
    file.write_group("reference", a);
  }

  const system::InvariantValues initial = invariants.evaluate(scene.initial);

  struct Printed {
    std::string scheme, step, steps, rhs, error, cpu_min, cpu_median, status;
  };
  std::vector<Printed> printed;

  for (std::size_t j = 0; j < jobs.size(); ++j) {
    const Job& job = jobs[j];
    const integrators::SchemeInfo& scheme = *job.scheme;
    const std::string step_text = job.dt ? "dt=" + format_g(*job.dt) : "tol=" + format_g(*job.tol);
    if (progress)
      std::cerr << "\r\033[Kwork-precision: " << j + 1 << '/' << jobs.size() << ' ' << scheme.name << ' ' << step_text
                << std::flush;

    ResultRow row = file.row();
    row.set("scheme", scheme.name);
    if (job.dt) row.set("dt", *job.dt);
    if (job.tol) row.set("tol", *job.tol);
    row.set("repeats", 0);
    row.set("below_reference_floor", 0);
    Printed p{scheme.name, step_text, "-", "-", "-", "-", "-", ""};

    if (const std::string why = integrators::unsupported_reason(scheme, model); !why.empty()) {
      row.set("status", "refused: " + why);
      p.status = "refused: " + why;
      file.append(row);
      printed.push_back(p);
      continue;
    }
    const integrators::RunConfig cfg = make_config(t_end, job.dt, job.tol);
    const RunResult first = run_once(scheme, model, scene.initial, cfg);
    if (!first.threw) {
      row.set("steps", first.stats.steps);
      row.set("rejected_steps", first.stats.work.rejected_steps);
      row.set("rhs_evaluations", first.stats.work.rhs_evaluations);
      p.steps = std::to_string(first.stats.steps);
      p.rhs = std::to_string(first.stats.work.rhs_evaluations);
    }
    if (!first.stats.ok) {
      row.set("status", "failed: " + first.stats.status);
      p.status = "failed: " + first.stats.status;
      file.append(row);
      printed.push_back(p);
      continue;
    }

    const GlobalError err = global_error(first.final, ref.state);
    const double floor = row_floor(ref.estimated_error, ref.amplification, first.stats.steps);
    row.set("error_floor", floor);
    const bool below_floor = err.max < floor;
    if (below_floor) {
      row.set("below_reference_floor", 1);
      p.error = "<" + format_e(floor);
    } else {
      row.set("error_attitude", err.attitude);
      row.set("error_momentum", err.momentum);
      row.set("error", err.max);
      p.error = format_e(err.max);
    }
    const system::InvariantValues fin = invariants.evaluate(first.final);
    std::size_t c = 0;
    if (invariants.energy_conserved())
      row.set(invariant_columns[c++], system::relative_error(fin.energy, initial.energy));
    for (std::size_t k = 0; k < invariants.scalar_names().size(); ++k)
      row.set(invariant_columns[c++], system::relative_error(fin.scalars[k], initial.scalars[k]));
    if (invariants.free_body()) {
      const double m0 = initial.space_momentum.norm();
      const double d = (fin.space_momentum - initial.space_momentum).norm();
      row.set(invariant_columns[c++], m0 > 0.0 ? d / m0 : d);
    }
    row.set(invariant_columns[c++], fin.orthogonality_error);

    // Timed runs: the same run again, nothing observed but the final state.
    std::vector<double> times;
    std::string timing_failure;
    for (int r = 0; r < o.repeat; ++r) {
      const RunResult again = run_once(scheme, model, scene.initial, cfg);
      if (!again.stats.ok) {
        timing_failure = again.stats.status;
        break;
      }
      times.push_back(again.stats.cpu_seconds);
    }
    if (!timing_failure.empty()) {
      row.set("status", "failed in a timed repeat: " + timing_failure);
      p.status = "failed in a timed repeat";
    } else {
      std::sort(times.begin(), times.end());
      const std::size_t n = times.size();
      const double median = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
      row.set("cpu_seconds_min", times.front());
      row.set("cpu_seconds_median", median);
      row.set("repeats", static_cast<std::int64_t>(n));
      row.set("status", "ok");
      p.cpu_min = format_e(times.front());
      p.cpu_median = format_e(median);
      p.status = "ok";
    }
    file.append(row);
    printed.push_back(p);
  }
  if (progress) std::cerr << "\r\033[K" << std::flush;

  ResultAttributes diag;
  diag.text["status"] = "ok";
  diag.integer["rows"] = static_cast<std::int64_t>(jobs.size());
  diag.number["cpu_seconds"] = integrators::detail::cpu_now() - cpu0;
  file.finish(diag);

  if (!o.quiet) {
    std::cout << "reference: kind=" << ref.kind << " scheme=" << ref.scheme;
    if (ref.kind == "converged") std::cout << " tol=" << format_g(ref.tol);
    std::cout << " estimated_error=" << format_e(ref.estimated_error) << " t_end=" << format_g(t_end, 17) << '\n';
    std::size_t w_scheme = 6, w_step = 7, w_status = 6;
    for (const auto& p : printed) {
      w_scheme = std::max(w_scheme, p.scheme.size());
      w_step = std::max(w_step, p.step.size());
      w_status = std::max(w_status, p.status.size());
    }
    char line[512];
    std::snprintf(line, sizeof line, "%-*s  %-*s  %10s  %12s  %10s  %10s  %10s  %s\n", static_cast<int>(w_scheme),
                  "scheme", static_cast<int>(w_step), "dt/tol", "steps", "rhs_evals", "error", "cpu_min_s", "cpu_med_s",
                  "status");
    std::cout << line;
    for (const auto& p : printed) {
      std::snprintf(line, sizeof line, "%-*s  %-*s  %10s  %12s  %10s  %10s  %10s  ", static_cast<int>(w_scheme),
                    p.scheme.c_str(), static_cast<int>(w_step), p.step.c_str(), p.steps.c_str(), p.rhs.c_str(),
                    p.error.c_str(), p.cpu_min.c_str(), p.cpu_median.c_str());
      std::cout << line << p.status << '\n';
    }
    std::cout << "wrote " << file.path() << " and " << file.csv_path() << '\n';
  }
  return exit_ok;
}

}  // namespace

Subcommand add_work_precision_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<WorkPrecisionOptions>();
  auto* sub = app.add_subcommand(
      "work-precision",
      "Error at t_end against a reference (exact flow for free bodies, else rkmk-dp54 at tol 1e-14 with its error "
      "estimated against tol 1e-13) and CPU time "
      "(min and median of N runs) for each scheme and step or tolerance");
  sub->add_option("--scene", o->scene, "Scene file (TOML)")->required();
  sub->add_option("--schemes", o->schemes, "Comma-separated scheme names, no spaces (see `lgi schemes`)")
      ->required()
      ->allow_extra_args(false)
      ->delimiter(',')
      ->type_name("A,B,...");
  sub->add_option("--dt", o->dt,
                  "Comma-separated steps for the fixed-step schemes. Default: the scene's [run] dt times 1, 1/2, 1/4, "
                  "1/8")
      ->allow_extra_args(false)
      ->delimiter(',')
      ->type_name("H1,H2,...");
  sub->add_option("--tol", o->tol,
                  "Comma-separated tolerances for the adaptive schemes. Default: the scene's [run] tol times 1, 1e-1, "
                  "1e-2, 1e-3")
      ->allow_extra_args(false)
      ->delimiter(',')
      ->type_name("T1,T2,...");
  sub->add_option("--t-end", o->t_end, "Final time. Default: the scene's [run] t_end (needed if it has none)");
  sub->add_option("--repeat", o->repeat, "Timed runs per row (CPU time: min and median)")->capture_default_str();
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV goes beside it, .csv in place of .h5 (out.h5 -> out.csv)")->required();
  sub->add_flag("--force", o->force, "Overwrite existing output files");
  sub->add_flag("--quiet", o->quiet, "Print nothing but errors");
  return {sub, [o, context] {
            o->command_line = context.command_line;
            return work_precision(*o);
          }};
}

}  // namespace lgi::experiments
