// lgi actions --scene FILE --out FILE.h5 [--h H [--grid N] [--l L1,L2,.. --tori N | --l L --k K]]
//             [--scheme S] [--dt DT] [--crossings N] [--harmonics M] [--force] [--quiet]
// The action variables of the tori of an integrable top (analysis/actions.hpp;
// formulas: docs/actions.md; layout: experiments/ACTIONS.md). Without --h:
// the torus of the scene's initial state, in closed form (Lagrange, Euler)
// and numerically from the flow. With --h: the energy surface H = h in action
// space, on a grid (closed forms) or from --tori numerical tori at each --l;
// with --k (a Kovalevskaya top): the torus through the level (h, l, k), with
// the Maslov indices of its cycles (analysis/kovalevskaya_torus.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/analysis/actions.hpp"
#include "experiments/analysis/kovalevskaya_diagram.hpp"
#include "experiments/analysis/kovalevskaya_torus.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/cli/work_limits.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "integrators/registry/registry.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

struct ActionsOptions {
  std::string scene, out, scheme = experiments::NumericalTorusOptions::default_scheme;
  std::optional<double> h, dt, k;
  std::vector<double> l;
  int grid = 61, tori = 12, crossings = 400, harmonics = NumericalTorusOptions{}.harmonics;
  bool force = false, quiet = false;
  std::string command_line;
};

enum Method : std::int64_t { closed_lagrange = 0, closed_euler = 1, numerical = 2 };

struct Row {
  Method method = numerical;
  Vec3 actions = Vec3::Zero(), frequencies = Vec3::Zero();
  double h = 0.0, rotation_number = nan(), return_time = nan(), fit_residual = nan();
  bool ok = true;
  int reason = 0;       // method 2: a TorusFailure (experiments/ACTIONS.md)
  int section = -1;     // method 2: the section's coordinate of (Π, Γ), 0..5 (−1: none)
  std::string status;   // method 2: the printed status
  double k = nan();                   // --k: the level's k = K/c²
  double mu_a = nan(), mu_b = nan();  // --k: the Maslov indices of cycles a and b
  double slow = nan(), fast = nan();  // --k: the actions in the libration basis (docs/quantum.md §10)
  static double nan() { return std::numeric_limits<double>::quiet_NaN(); }
};

HeavyTopBody heavy_top(const system::Scene& scene) {
  const bool gravity = scene.declared<system::GravityTerm>().has_value();
  if (!scene.is_free_body() && !scene.declares_only<system::GravityTerm>())
    throw InputError(scene.file + ": lgi actions needs a heavy top (gravity and no other torque term) or a free body");
  HeavyTopBody body;
  body.J = scene.inertia;
  if (gravity)
    body.weight = *scene.mass * scene.declared<system::GravityTerm>()->g * scene.center_of_mass.value_or(Vec3::Zero());
  return body;
}

/// The principal moments of a diagonal J with distinct moments (the Euler closed form).
std::optional<Vec3> euler_moments(const system::Scene& scene) {
  if (!scene.is_free_body()) return std::nullopt;
  const Mat3& J = scene.inertia;
  if (!J.isDiagonal(1e-14 * J.norm())) return std::nullopt;
  const Vec3 d = J.diagonal();
  if (d[0] == d[1] || d[1] == d[2] || d[0] == d[2]) return std::nullopt;
  return d;
}

Row numerical_row(const system::Scene& scene, const system::State& x, const ActionsOptions& o) {
  NumericalTorusOptions opt;
  opt.scheme = o.scheme;
  opt.dt = o.dt.value_or(scene.dt.value_or(1e-2));
  opt.crossings = o.crossings;
  opt.harmonics = o.harmonics;
  const NumericalTorus t = numerical_torus(scene, x, opt);
  Row r;
  r.method = numerical;
  r.actions = {t.l, t.action_a, t.action_b};
  r.frequencies = {Row::nan(), t.omega_a, t.omega_b};
  r.h = t.h;
  r.rotation_number = t.rotation_number;
  r.return_time = t.return_time;
  r.fit_residual = t.fit_residual;
  r.ok = t.ok;
  r.reason = t.reason;
  r.section = t.section.coordinate;
  r.status = t.status;
  return r;
}

Row lagrange_row(const LagrangeActions& a, double h) {
  Row r;
  r.method = closed_lagrange;
  r.actions = a.actions;
  r.frequencies = a.frequencies;
  r.h = h;
  r.return_time = a.period;
  return r;
}

Row euler_row(const EulerActions& a, double h) {
  Row r;
  r.method = closed_euler;
  r.actions = a.actions;
  r.frequencies = a.frequencies;
  r.h = h;
  r.return_time = a.period;
  return r;
}

std::vector<Row> single_torus(const system::Scene& scene, const HeavyTopBody& body, const ActionsOptions& o) {
  std::vector<Row> rows;
  const system::State& x = scene.initial;
  const Vec3 gamma = x.R.row(2).transpose();
  const double l = x.Pi.dot(gamma), h = 0.5 * x.Pi.dot(body.J.inverse() * x.Pi) + body.weight.dot(gamma);
  if (const auto lb = lagrange_body(body)) {
    if (const auto a = lagrange_actions(*lb, l, x.Pi.z(), h)) rows.push_back(lagrange_row(*a, h));
  } else if (const auto moments = euler_moments(scene)) {
    if (const auto a = euler_actions(*moments, x.Pi, l)) rows.push_back(euler_row(*a, h));
  }
  const Row r = numerical_row(scene, x, o);
  if (!interrupt_requested.load()) rows.push_back(r);  // a torus a signal may have cut short is not kept
  return rows;
}

/// --k: the Kovalevskaya torus through a point of {H = h, C = l, k} (analysis/kovalevskaya_torus.hpp).
std::vector<Row> level_torus(const system::Scene& scene, const HeavyTopBody& body, const ActionsOptions& o) {
  const double l = o.l.front(), h = *o.h, k = *o.k;
  const std::optional<StateVec6> x = kovalevskaya_level_point(body, l, h, k, std::nullopt);
  if (!x)
    throw InputError("--k: no point of {H = " + format_general(h, 6) + ", l = " + format_general(l, 6) +
                     ", k = " + format_general(k, 6) + "} found on " + scene.file + " (outside the attained range?)");
  NumericalTorusOptions opt;
  opt.scheme = o.scheme;
  opt.dt = o.dt.value_or(scene.dt.value_or(1e-2));
  opt.crossings = o.crossings;
  opt.harmonics = o.harmonics;
  const system::State x0 = state_at(*x);
  Row r = numerical_row(scene, x0, o);
  const KovalevskayaTorus t = kovalevskaya_torus(scene, body, x0, opt);
  if (interrupt_requested.load()) return {};  // maybe cut short: not kept
  r.k = t.k;
  if (t.maslov.ok) r.mu_a = t.maslov.mu_a, r.mu_b = t.maslov.mu_b;
  else if (r.ok) r.status += "; Maslov indices not found: " + t.maslov.status;
  if (t.basis.ok) r.slow = t.basis.action_slow, r.fast = t.basis.action_fast;
  return {r};
}

std::vector<Row> energy_surface(const system::Scene& scene, const HeavyTopBody& body, const ActionsOptions& o) {
  std::vector<Row> rows;
  const double h = *o.h;
  if (o.k) return level_torus(scene, body, o);
  if (o.l.empty()) {
    // Ctrl-C: the closed-form grid reads the flag every row; the rows so far go to <out>.partial.
    const auto keep_going = [] { return !interrupt_requested.load(); };
    if (const auto lb = lagrange_body(body)) {
      for (const auto& a : lagrange_surface(*lb, h, o.grid, keep_going)) rows.push_back(lagrange_row(a, h));
      return rows;
    }
    if (const auto moments = euler_moments(scene)) {
      for (const auto& a : euler_surface(*moments, h, o.grid, keep_going)) rows.push_back(euler_row(a, h));
      return rows;
    }
    throw UsageError("--l: " + scene.file + " has no closed form; give the momenta l of the numerical tori");
  }
  // Progress on stderr (cli/sweep_progress.hpp; issue 50, item 8): a torus takes up to seconds.
  SweepProgress progress(o.quiet, static_cast<std::int64_t>(o.l.size()) * o.tori, 0, "actions", "tori");
  // Ctrl-C: the tori read the flag every step (actions_support.hpp); the one it cut short is not kept.
  std::int64_t done = 0, failed = 0;
  for (std::size_t i = 0; i < o.l.size() && !interrupt_requested.load(); ++i)
    for (const auto& x : level_set_states(body, o.l[i], h, o.tori)) {
      const Row r = numerical_row(scene, x, o);
      if (interrupt_requested.load()) break;
      rows.push_back(r);
      failed += r.ok ? 0 : 1;
      progress.update(++done, failed);
    }
  progress.finish();
  return rows;
}

std::vector<TableColumn> columns_of(const std::vector<Row>& rows) {
  std::vector<TableColumn> c = {{"method", 1, true}, {"actions", 3}, {"h"}, {"frequencies", 3},
                                {"rotation_number"}, {"return_time"}, {"fit_residual"}, {"ok", 1, true},
                                {"reason", 1, true}, {"section", 1, true}, {"k"}, {"maslov", 2},
                                {"libration_actions", 2}};
  for (const auto& r : rows) {
    c[0].whole.push_back(r.method);
    c[1].real.insert(c[1].real.end(), r.actions.data(), r.actions.data() + 3);
    c[2].real.push_back(r.h);
    c[3].real.insert(c[3].real.end(), r.frequencies.data(), r.frequencies.data() + 3);
    c[4].real.push_back(r.rotation_number);
    c[5].real.push_back(r.return_time);
    c[6].real.push_back(r.fit_residual);
    c[7].whole.push_back(r.ok ? 1 : 0);
    c[8].whole.push_back(r.reason);
    c[9].whole.push_back(r.section);
    c[10].real.push_back(r.k);
    c[11].real.insert(c[11].real.end(), {r.mu_a, r.mu_b});
    c[12].real.insert(c[12].real.end(), {r.slow, r.fast});
  }
  return c;
}

void check_flags(const ActionsOptions& o) {
  if (o.h && !std::isfinite(*o.h)) throw UsageError("--h: must be a finite number");
  for (const double l : o.l)
    if (!std::isfinite(l)) throw UsageError("--l: the values must be finite numbers");
  if (!o.l.empty() && !o.h) throw UsageError("--l: only with --h");
  if (o.k && (!std::isfinite(*o.k) || !o.h || o.l.size() != 1))
    throw UsageError("--k: needs a finite value, --h and exactly one --l");
  if (o.grid < 2 || o.grid > 2000) throw UsageError("--grid: must be between 2 and 2000");
  if (o.tori < 1) throw UsageError("--tori: must be at least 1");
  check_work_limit("--tori", saturating_product(o.tori, std::max<std::int64_t>(1, static_cast<std::int64_t>(o.l.size()))),
                   max_tori, "tori (--tori x the values of --l)");
  if (o.crossings < 16) throw UsageError("--crossings: must be at least 16");
  if (o.harmonics < 8 || o.harmonics > 512) throw UsageError("--harmonics: must be between 8 and 512");
  // The tori run to --crossings crossings, whatever their length: a step below 1e-6 is days of work (issue 50).
  if (o.dt && !(*o.dt >= 1e-6 && *o.dt <= 1.0)) throw UsageError("--dt: must be in [1e-6, 1]");
  const integrators::SchemeInfo* info = integrators::find_scheme(o.scheme);
  if (info == nullptr) throw UsageError("--scheme: unknown scheme " + o.scheme);
  // The tori need every step on a fixed grid and their section crossings located (actions_torus.cpp).
  if (info->properties.adaptive || !info->locates_events)
    throw UsageError("--scheme: " + o.scheme + " is " + (info->properties.adaptive ? "adaptive" : "not event-locating") +
                     "; the numerical tori need a fixed-step scheme that locates events");
}

int run_actions(const ActionsOptions& o) {
  const system::Scene scene = read_scene(o.scene);
  refuse_cardan_scene(scene, "actions");
  const HeavyTopBody body = heavy_top(scene);
  check_flags(o);
  if (o.k && !kovalevskaya_scale(body))
    throw InputError("--k: " + scene.file + " is not a Kovalevskaya top (J = J3 diag(2, 2, 1), centre of mass on e1)");
  hdf5::check_output_target(o.out, o.force);  // before the tori, not after them
  const InterruptGuard interrupt_guard;  // Ctrl-C / SIGTERM: the tori so far go to <out>.partial
  const std::vector<Row> rows = o.h ? energy_surface(scene, body, o) : single_torus(scene, body, o);
  std::map<std::string, std::string> parameters = {
      {"subcommand", "actions"},      {"command_line", o.command_line},  {"scene_file", scene.file},
      {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
      {"cxx_flags", build_info::cxx_flags}, {"scheme", o.scheme},          {"crossings", std::to_string(o.crossings)},
      {"harmonics", std::to_string(o.harmonics)},
      {"methods", "0: Lagrange closed form (l, L3, I_theta); 1: Euler closed form (l, G, I_l); "
                  "2: numerical (l, I_a, I_b)"}};
  if (o.h) parameters["h"] = format_general(*o.h, 17);
  if (o.k) parameters["k"] = format_general(*o.k, 17);
  if (interrupt_signal() != 0) {  // the HDF5 file alone, as <out>.partial (no CSV): an incomplete table
    const std::string partial = o.out + ".partial";
    parameters["status"] = "interrupted by signal: " + std::to_string(rows.size()) + " rows";
    write_groups_file(partial, true, {{"tori", columns_of(rows), {}}}, parameters);
    std::cerr << "lgi: actions interrupted by signal; the " << rows.size() << " rows finished are in " << partial
              << '\n';
    return interrupted_exit_status();
  }
  write_table_file(o.out, o.force, "tori", columns_of(rows), parameters);
  if (o.quiet) return exit_ok;
  if (o.k) {
    const Row& r = rows.front();
    std::printf("method=numerical h=%.10g l=%.10g k=%.10g actions=(%.10g, %.10g) frequencies=(%.10g, %.10g) "
                "maslov=(%g, %g) libration_actions=(%.10g, %.10g) ok=%d status=%s\n",
                r.h, r.actions[0], r.k, r.actions[1], r.actions[2], r.frequencies[1], r.frequencies[2], r.mu_a,
                r.mu_b, r.slow, r.fast, r.ok ? 1 : 0, r.status.c_str());
    return exit_ok;
  }
  if (o.h) {
    std::size_t failures = 0;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (!rows[i].ok) {
        ++failures;
        std::printf("torus %zu (l = %.6g): failed, reason %d: %s\n", i, rows[i].actions[0], rows[i].reason,
                    rows[i].status.c_str());
      }
    std::cout << rows.size() << " tori on H = " << format_general(*o.h, 6) << ", " << rows.size() - failures
              << " ok; wrote " << o.out << '\n';
    return exit_ok;
  }
  for (const auto& r : rows)
    std::printf("method=%s h=%.6g actions=(%.10g, %.10g, %.10g) frequencies=(%.10g, %.10g, %.10g) ok=%d%s%s\n",
                r.method == closed_lagrange ? "lagrange" : r.method == closed_euler ? "euler" : "numerical", r.h,
                r.actions[0], r.actions[1], r.actions[2], r.frequencies[0], r.frequencies[1], r.frequencies[2],
                r.ok ? 1 : 0, r.method == numerical ? " status=" : "", r.method == numerical ? r.status.c_str() : "");
  return exit_ok;
}

}  // namespace

Subcommand add_actions_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<ActionsOptions>();
  auto* sub = app.add_subcommand(
      "actions",
      "Action variables of the tori of an integrable top: the scene's torus, or the energy surface H = h in action "
      "space (--h), in closed form (Lagrange, Euler) or numerically from the flow (experiments/ACTIONS.md)");
  sub->add_option("--scene", o->scene, "Scene file (TOML): a heavy top, or a free body")->required();
  sub->add_option("--h", o->h, "The energy of the surface; without it, the torus of the scene's initial state");
  sub->add_option("--l", o->l, "With --h: the momenta l of the numerical tori (comma-separated)")->delimiter(',');
  sub->add_option("--grid", o->grid, "With --h and a closed form: grid points per axis")->capture_default_str();
  sub->add_option("--k", o->k,
                  "With --h and one --l, a Kovalevskaya top: the torus through a point of the level (h, l, k), "
                  "k = K/c^2, with the Maslov indices of its cycles");
  sub->add_option("--tori", o->tori, "With --l: numerical tori per l")->capture_default_str();
  sub->add_option("--scheme", o->scheme, "Scheme of the numerical tori")->capture_default_str();
  sub->add_option("--dt", o->dt, "Step of the numerical tori. Default: the scene's [run] dt, else 0.01");
  sub->add_option("--crossings", o->crossings, "Section crossings per numerical torus")->capture_default_str();
  sub->add_option("--harmonics", o->harmonics, "Most Fourier modes of a numerical torus's section curve")
      ->capture_default_str();
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV beside it")->required();
  add_force_quiet_flags(*sub, *o, "Replace existing output files");
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_actions(*o);
          },
          [o] { check_flags(*o); }};
}

}  // namespace lgi::experiments
