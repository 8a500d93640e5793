// lgi work-precision: global error at t_end against a reference, and CPU
// time per run (min and median over N timed repeats, each a batch of
// back-to-back runs that write nothing), for each scheme
// and each step (fixed-step schemes: --dt) or tolerance (adaptive: --tol).
// Layout of the result file: experiments/RESULTS.md.
//
// The reference (/reference in the file) and the error measure:
// reference_solution.hpp.
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

#include "experiments/analysis/reference_solution.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/cli/run_parameters.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/step_settings.hpp"
#include "experiments/cli/write_failures.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/results_file.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "integrators/registry/registry.hpp"
#include "integrators/core/loop_support.hpp"
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

/// The checks of the lists that need no scene; returns the schemes.
std::vector<const integrators::SchemeInfo*> checked_lists(const WorkPrecisionOptions& o) {
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
    if (!(h > 0.0 && std::isfinite(h))) throw UsageError("--dt: every step must be a finite number > 0, got " + format_general(h, 6));
  for (double t : o.tol)
    if (!(t > 0.0 && std::isfinite(t)))
      throw UsageError("--tol: every tolerance must be a finite number > 0, got " + format_general(t, 6));
  if (o.repeat < 1) throw UsageError("--repeat: must be >= 1");
  return schemes;
}

std::vector<Job> plan(const WorkPrecisionOptions& o) {
  const std::vector<const integrators::SchemeInfo*> schemes = checked_lists(o);
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

/// The /results columns (RESULTS.md); `invariant_columns` gets the invariant error columns' names.
std::vector<Column> result_columns(const system::SceneInvariants& invariants,
                                   std::vector<std::string>& invariant_columns) {
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
  invariant_columns.clear();
  for (const auto& n : invariants.error_names()) invariant_columns.push_back("error_" + n);
  for (const auto& c : invariant_columns) columns.push_back({c, ColumnType::real, ""});
  for (const char* c : {"cpu_seconds_min", "cpu_seconds_median"}) columns.push_back({c, ColumnType::real, "s"});
  columns.push_back({"repeats", ColumnType::integer, ""});
  columns.push_back({"status", ColumnType::text, ""});
  columns.push_back({"below_reference_floor", ColumnType::integer, ""});
  columns.push_back({"error_floor", ColumnType::real, ""});
  columns.push_back({"runs_per_repeat", ColumnType::integer, ""});
  return columns;
}

void write_reference_group(ResultsFile& file, const Reference& ref, double t_end) {
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

/// A row as printed on stdout.
struct Printed {
  std::string scheme, step, steps, rhs, error, cpu_min, cpu_median, status;
};

/// What every row of one work-precision run shares.
struct Study {
  const system::Scene& scene;
  const system::AnyModel& model;
  const system::SceneInvariants& invariants;
  std::vector<std::string> invariant_columns;
  system::InvariantValues initial;
  Reference reference;
  double t_end;
  int repeat;
};

/// The error against the reference (or the floor it is under) and the invariant errors of a run's final state.
void set_errors(const Study& st, const RunResult& run, ResultRow& row, Printed& p) {
  const GlobalError err = global_error(run.final, st.reference.state);
  const double floor = row_floor(st.reference.estimated_error, st.reference.amplification, run.stats.steps);
  row.set("error_floor", floor);
  if (err.max < floor) {
    row.set("below_reference_floor", 1);
    p.error = "<" + format_sci(floor);
  } else {
    row.set("error_attitude", err.attitude);
    row.set("error_momentum", err.momentum);
    row.set("error", err.max);
    p.error = format_sci(err.max);
  }
  std::vector<double> errors;
  st.invariants.errors(st.initial, st.invariants.evaluate(run.final), errors);
  for (std::size_t c = 0; c < errors.size(); ++c) row.set(st.invariant_columns[c], errors[c]);
}

/// A timed repeat lasts at least this long (CPU seconds).
constexpr double repeat_seconds = 1e-3;

/// Runs in one timed repeat: enough back-to-back runs to last repeat_seconds,
/// judged from the first run's time. The thread CPU clock is a system call
/// (~3 µs on a virtual machine, as long as a tenth of a short run), so it is
/// read once around the batch instead of around each run, as timeit and
/// Google Benchmark do.
std::int64_t runs_per_repeat(double first_run_seconds) {
  if (!(first_run_seconds > 0.0)) return 1;
  return static_cast<std::int64_t>(std::clamp(std::ceil(repeat_seconds / first_run_seconds), 1.0, 1e5));
}

/// Timed runs: `repeat` batches of `runs` back-to-back runs of the row, each
/// observing nothing but the final state; a repeat's time is its batch's CPU
/// time over `runs` (the scheme's setup and its stepper loop, per run).
/// False if a signal cut one short.
bool set_timing(const Study& st, const integrators::SchemeInfo& scheme, integrators::RunConfig cfg,
                std::int64_t runs, ResultRow& row, Printed& p) {
  cfg.cpu_clock = false;  // timed around the batch
  std::vector<double> times;
  for (int r = 0; r < st.repeat; ++r) {
    const double cpu0 = integrators::detail::cpu_now();
    for (std::int64_t k = 0; k < runs; ++k) {
      const RunResult again = run_once(scheme, st.model, st.scene.initial, cfg);
      if (again.stats.interrupted) return false;
      if (!again.stats.ok) {
        row.set("status", "failed in a timed repeat: " + again.stats.status);
        p.status = "failed in a timed repeat";
        return true;
      }
    }
    times.push_back((integrators::detail::cpu_now() - cpu0) / static_cast<double>(runs));
  }
  std::sort(times.begin(), times.end());
  const std::size_t n = times.size();
  const double median = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
  row.set("cpu_seconds_min", times.front());
  row.set("cpu_seconds_median", median);
  row.set("repeats", static_cast<std::int64_t>(n));
  row.set("runs_per_repeat", runs);
  row.set("status", "ok");
  p.cpu_min = format_sci(times.front());
  p.cpu_median = format_sci(median);
  p.status = "ok";
  return true;
}

/// One row: refused, failed, or measured (errors, then timing). Nothing if a
/// signal cut one of its runs short (the row is not a result, and not written).
std::optional<Printed> measure(const Study& st, const Job& job, const std::string& step_text, ResultsFile& file) {
  const integrators::SchemeInfo& scheme = *job.scheme;
  ResultRow row = file.row();
  row.set("scheme", scheme.name);
  if (job.dt) row.set("dt", *job.dt);
  if (job.tol) row.set("tol", *job.tol);
  row.set("repeats", 0);
  row.set("runs_per_repeat", 0);
  row.set("below_reference_floor", 0);
  Printed p{scheme.name, step_text, "-", "-", "-", "-", "-", ""};
  integrators::RunConfig cfg = make_config(st.t_end, job.dt, job.tol);
  cfg.stop = &interrupt_requested;  // Ctrl-C ends a long run after its current step
  if (const std::string why = integrators::unsupported_reason(scheme, st.model); !why.empty()) {
    row.set("status", "refused: " + why);
    p.status = "refused: " + why;
  } else if (const RunResult first = run_once(scheme, st.model, st.scene.initial, cfg); !first.stats.ok) {
    if (first.stats.interrupted) return std::nullopt;
    if (!first.threw) {
      row.set("steps", first.stats.steps);
      row.set("rejected_steps", first.stats.work.rejected_steps);
      row.set("rhs_evaluations", first.stats.work.rhs_evaluations);
      p.steps = std::to_string(first.stats.steps);
      p.rhs = std::to_string(first.stats.work.rhs_evaluations);
    }
    row.set("status", "failed: " + first.stats.status);
    p.status = "failed: " + first.stats.status;
  } else {
    row.set("steps", first.stats.steps);
    row.set("rejected_steps", first.stats.work.rejected_steps);
    row.set("rhs_evaluations", first.stats.work.rhs_evaluations);
    p.steps = std::to_string(first.stats.steps);
    p.rhs = std::to_string(first.stats.work.rhs_evaluations);
    set_errors(st, first, row, p);
    if (!set_timing(st, scheme, cfg, runs_per_repeat(first.stats.cpu_seconds), row, p)) return std::nullopt;
  }
  file.append(row);
  return p;
}

/// Every row, each written as it is made; false if a signal stopped them
/// (the rows before are in the file).
bool measure_rows(const Study& st, const std::vector<Job>& jobs, bool progress, ResultsFile& file,
                  std::vector<Printed>& printed) {
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    const Job& job = jobs[j];
    const std::string step_text = job.dt ? "dt=" + format_general(*job.dt, 3) : "tol=" + format_general(*job.tol, 3);
    if (progress)
      std::cerr << "\r\033[Kwork-precision: " << j + 1 << '/' << jobs.size() << ' ' << job.scheme->name << ' '
                << step_text << std::flush;
    std::optional<Printed> p = measure(st, job, step_text, file);
    if (!p) return false;
    printed.push_back(std::move(*p));
  }
  return true;
}

/// A signal ended the command: the rows so far stay in the .partial files.
int abandon_interrupted(ResultsFile& file, std::size_t rows, double cpu_seconds) {
  ResultAttributes diag;
  diag.text["status"] = integrators::interrupted_status;
  diag.integer["rows"] = static_cast<std::int64_t>(rows);
  diag.number["cpu_seconds"] = cpu_seconds;
  file.abandon(diag);
  std::cerr << "lgi: work-precision " << integrators::interrupted_status << " after " << rows
            << " rows; partial results kept in " << file.partial_path() << " and " << file.csv_partial_path() << '\n';
  return interrupted_exit_status();
}

void print_table(const Reference& ref, double t_end, const std::vector<Printed>& printed) {
  std::cout << "reference: kind=" << ref.kind << " scheme=" << ref.scheme;
  if (ref.kind == "converged") std::cout << " tol=" << format_general(ref.tol, 3);
  std::cout << " estimated_error=" << format_sci(ref.estimated_error) << " t_end=" << format_general(t_end, 17) << '\n';
  std::size_t w_scheme = 6, w_step = 7;
  for (const auto& p : printed) {
    w_scheme = std::max(w_scheme, p.scheme.size());
    w_step = std::max(w_step, p.step.size());
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
}

/// The jobs with the command line's lists, else the scene's defaults (step_settings.hpp); warns about
/// a list given on the command line that no scheme uses.
std::vector<Job> resolved_jobs(const WorkPrecisionOptions& o, const system::Scene& scene,
                               WorkPrecisionOptions& resolved) {
  resolved = o;
  resolved.dt = default_step_list(o.dt, scene.dt);
  resolved.tol = default_tolerance_list(o.tol, scene.tol);
  std::vector<Job> jobs = plan(resolved);
  if (!o.quiet) {
    const bool any_fixed = std::any_of(jobs.begin(), jobs.end(), [](const Job& j) { return j.dt.has_value(); });
    const bool any_adaptive = std::any_of(jobs.begin(), jobs.end(), [](const Job& j) { return j.tol.has_value(); });
    if (!o.dt.empty() && !any_fixed) std::cerr << "lgi: warning: --dt ignored: no fixed-step scheme in --schemes\n";
    if (!o.tol.empty() && !any_adaptive) std::cerr << "lgi: warning: --tol ignored: no adaptive scheme in --schemes\n";
  }
  return jobs;
}

int work_precision(const WorkPrecisionOptions& o) {
  const system::Scene scene = read_scene(o.scene);
  refuse_cardan_scene(scene, "work-precision");
  WorkPrecisionOptions resolved;
  const std::vector<Job> jobs = resolved_jobs(o, scene, resolved);
  const double t_end = resolve_t_end(o.t_end, scene, /*allow_zero=*/false);
  // A step that cannot advance time is bad input (issue 50), not a failed row of a run that exits 0.
  for (const Job& j : jobs)
    if (j.dt)
      if (const std::string why = integrators::fixed_step_grid_problem(0.0, t_end, *j.dt); !why.empty())
        throw UsageError("--dt: " + why);
  const system::AnyModel model = system::make_model(scene);
  const system::SceneInvariants invariants(scene, model);
  const bool progress = !o.quiet && ::isatty(STDERR_FILENO) == 1;

  Study st{scene, model, invariants, {}, invariants.evaluate(scene.initial), {}, t_end, o.repeat};
  // Signals only set the flag from before the first file exists until the results are published (interrupt_guard.hpp).
  const InterruptGuard interrupt_guard;  // the reference's runs and the rows' read the flag every step
  ResultsFile file(o.out, o.force, result_columns(invariants, st.invariant_columns));
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
  try {
    st.reference = compute_reference(scene, model, t_end, &interrupt_requested);
  } catch (const ReferenceInterrupted&) {
    if (progress) std::cerr << "\r\033[K" << std::flush;
    return abandon_interrupted(file, 0, integrators::detail::cpu_now() - cpu0);
  } catch (const RunError& e) {
    ResultAttributes diag;
    diag.text["status"] = e.what();
    file.abandon(diag);
    if (progress) std::cerr << '\n';
    std::cerr << "lgi: " << e.what() << "; partial results kept in " << file.partial_path() << '\n';
    return exit_run_failed;
  }
  write_reference_group(file, st.reference, t_end);

  std::vector<Printed> printed;
  const bool complete = measure_rows(st, jobs, progress, file, printed);
  if (progress) std::cerr << "\r\033[K" << std::flush;
  if (!complete) return abandon_interrupted(file, printed.size(), integrators::detail::cpu_now() - cpu0);

  ResultAttributes diag;
  diag.text["status"] = "ok";
  diag.integer["rows"] = static_cast<std::int64_t>(jobs.size());
  diag.number["cpu_seconds"] = integrators::detail::cpu_now() - cpu0;
  file.finish(diag);
  if (!o.quiet) {
    print_table(st.reference, t_end, printed);
    std::cout << "wrote " << file.path() << " and " << file.csv_path() << '\n';
  }
  return exit_ok;
}

}  // namespace

Subcommand add_work_precision_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<WorkPrecisionOptions>();
  auto* sub = app.add_subcommand(
      "work-precision",
      "Error at t_end against a reference (exact flow for free bodies, else rkmk-dop853 at tol 1e-14 with its error "
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
  sub->add_option("--repeat", o->repeat, "Timed repeats per row, each a batch of back-to-back runs lasting >= 1 ms (CPU time per run: min and median)")->capture_default_str();
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV goes beside it, .csv in place of .h5 (out.h5 -> out.csv)")->required();
  add_force_quiet_flags(*sub, *o, "Overwrite existing output files");
  sub->footer(exit_status_help);
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_with_write_failures_as_run_errors([&] { return work_precision(*o); });
          },
          [o] {
            (void)checked_lists(*o);
            check_step_flags({std::nullopt, std::nullopt, o->t_end}, /*allow_zero_t_end=*/false);
          }};
}

}  // namespace lgi::experiments
