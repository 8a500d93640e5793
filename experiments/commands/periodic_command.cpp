// lgi periodic --scene FILE --l L (--from-equilibria | --seed-file F | --seeds-from-poincare P.h5 ...)
//              [--continue-in h|l] [--h-range A:B] [--l-range A:B] [--steps N] [--h-step D] [--l-step D]
//              [--manifolds N ...] [--dt DT] [--amplitude E] --out FILE.h5 [--force] [--quiet]
// Periodic orbits of a heavy top's Euler–Poisson flow (or of a Cardan top's
// flow reduced at p1 = ℓ, analysis/periodic/periodic_flow.hpp): the Lyapunov centre
// families of the linearly stable relative equilibria, or families from seeds
// or from points of a Poincaré section, continued in h at fixed ℓ or in ℓ at
// fixed h, and the manifolds of hyperbolic orbits on the section
// (analysis/periodic/, commands/periodic/; layout and method: experiments/PERIODIC.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "experiments/commands/periodic/critical_seeds.hpp"
#include "experiments/commands/periodic/periodic_run.hpp"
#include "experiments/commands/periodic/periodic_seeds.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/commands/atlas/atlas_tables.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

struct PeriodicOptions {
  std::string scene, out, seed_file, critical, h_range, l_range, poincare, poincare_rows, continue_in = "h";
  std::vector<std::string> poincare_points;
  std::optional<double> l;
  bool from_equilibria = false, no_events = false, no_branch_switching = false, switch_branches = false;
  int steps = 10, returns = 1, manifolds = 0, shooting_points = 1;
  double h_step = 0.01, l_step = 0.01, dt = 2e-3, amplitude = 1e-4;
  double manifold_periods = 4.0, manifold_epsilon = 1e-5;
  bool force = false, quiet = false;
  std::string command_line;
};

void check_flags(const PeriodicOptions& o) {
  const bool poincare = !o.poincare.empty();
  if (!poincare && (!o.l || !std::isfinite(*o.l))) throw UsageError("--l: must be a finite number");
  if (o.l && !std::isfinite(*o.l)) throw UsageError("--l: must be a finite number");
  if (int(o.from_equilibria) + int(!o.seed_file.empty()) + int(poincare) + int(!o.critical.empty()) != 1)
    throw UsageError("--from-equilibria / --seed-file / --seeds-from-poincare / --from-critical: give exactly one of them");
  if (poincare == (o.poincare_rows.empty() && o.poincare_points.empty()))
    throw UsageError(poincare ? "--seeds-from-poincare: give --poincare-rows or --poincare-point"
                              : "--poincare-rows / --poincare-point: only with --seeds-from-poincare");
  if (o.returns < 1 || o.returns > 1000) throw UsageError("--returns: must be in [1, 1000]");
  if (o.continue_in != "h" && o.continue_in != "l") throw UsageError("--continue-in: expected h or l");
  if (o.switch_branches && (o.no_branch_switching || o.no_events))
    throw UsageError("--switch-branches: not with --no-branch-switching or --no-events (it needs the located doublings)");
  if (o.shooting_points < 1 || o.shooting_points > 1000) throw UsageError("--shooting-points: must be in [1, 1000]");
  if (o.steps < 0 || o.steps > 100000) throw UsageError("--steps: must be in [0, 100000]");
  if (!(o.h_step > 0.0) || !std::isfinite(o.h_step)) throw UsageError("--h-step: must be a positive number");
  if (!(o.l_step != 0.0) || !std::isfinite(o.l_step)) throw UsageError("--l-step: must be a nonzero number");
  // ceil(T/dt) steps a shot, many shots a family: a step below 1e-6 is days of work (issue 50).
  if (!(o.dt >= 1e-6) || !(o.dt <= 1.0)) throw UsageError("--dt: must be in [1e-6, 1]");
  if (!(o.amplitude > 0.0) || !(o.amplitude <= 0.1)) throw UsageError("--amplitude: must be in (0, 0.1]");
  if (o.manifolds < 0 || o.manifolds > 100000) throw UsageError("--manifolds: must be in [0, 100000]");
  if (o.manifolds > 0 && !poincare) throw UsageError("--manifolds: only with --seeds-from-poincare (its section)");
  if (!(o.manifold_periods > 0.0) || !(o.manifold_periods <= 1000.0))
    throw UsageError("--manifold-periods: must be in (0, 1000]");
  if (!(o.manifold_epsilon > 0.0) || !(o.manifold_epsilon <= 0.1))
    throw UsageError("--manifold-epsilon: must be in (0, 0.1]");
}

/// --h-range / --l-range A:B, A < B.
std::pair<double, double> bounds(const std::string& text, const std::string& flag) {
  if (text.empty()) return {-INFINITY, INFINITY};
  const auto colon = text.find(':');
  double a = NAN, b = NAN;
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    std::size_t ia = 0, ib = 0;
    a = std::stod(text.substr(0, colon), &ia);
    b = std::stod(text.substr(colon + 1), &ib);
    if (ia != colon || ib != text.size() - colon - 1) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw UsageError(flag + ": expected A:B (two numbers), got '" + text + "'");
  }
  if (!(a < b) || !std::isfinite(a) || !std::isfinite(b)) throw UsageError(flag + ": need finite A < B");
  return {a, b};
}

std::string failures_text(const std::vector<std::string>& failures) {
  std::string t = failures.empty() ? "none" : "";
  for (const std::string& f : failures) t += (t.empty() ? "" : "; ") + f;
  return t;
}

/// The file's parameters: the command, the scene, the integrator and the continuation.
std::map<std::string, std::string> periodic_parameters(const PeriodicOptions& o, const system::Scene& scene, double l,
                                                       const std::vector<std::string>& failures) {
  const bool in_l = o.continue_in == "l";
  std::map<std::string, std::string> p{{"subcommand", "periodic"}, {"command_line", o.command_line}, {"scene_file", scene.file},
          {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version},
          {"l", format_general(l, 17)}, {"dt", format_general(o.dt, 17)},
          {"integrator", o.shooting_points == 1
                             ? "implicit midpoint, triple jump twice (order 6), ceil(T/dt) equal steps"
                             : "implicit midpoint, triple jump twice (order 6), ceil(T/(M dt)) equal steps a segment"},
          {"shooting_points", std::to_string(o.shooting_points)},
          {"continuation", in_l ? "pseudo-arclength in (x0, T, l) at fixed h after a first natural step in l"
                                : "pseudo-arclength in (x0, T, h) after a first natural step in h"},
          {"continue_in", o.continue_in},
          {"phase_condition", o.poincare.empty() ? "hyperplane through the guess, normal to the flow"
                                                 : "on the section of the poincare file"},
          {"seeds_from_poincare", o.poincare}, {"from_critical", o.critical},
          {"events", o.no_events ? "not located" : "fold, period_doubling, class_change (tr P = +-2)"},
          {"branch_switching", o.no_branch_switching || o.no_events ? "no" : "at period doublings"},
          {"failures", failures_text(failures)}};
  if (scene.suspension && !o.poincare.empty())
    p["phase_condition"] = "on the poincare file's section S = -sin(q2) dq2/dt = 0: the factor of each seed's piece "
                           "(dq2/dt = 0 on the pieces +-1, sin q2 = 0 on 2 and 3)";
  if (scene.suspension) {
    p["integrator"] = std::string("classical RK4 with its exact (dual-number) tangent flow on T^3 x R^3, ") +
                      (o.shooting_points == 1 ? "ceil(T/dt) equal steps" : "ceil(T/(M dt)) equal steps a segment");
    p["reduction"] = "Cardan top at p1 = l: q1 dropped (reset after each shot; its turn is cardan_drift), "
                     "q2, q3 modulo 2 pi";
  }
  return p;
}

/// Counts the starts on `progress` (made at the first call, when their number is known);
/// false once a signal came.
PeriodicRequest::StartDone progress_of_starts(std::optional<SweepProgress>& progress, bool quiet) {
  return [&progress, quiet](std::size_t done, std::size_t total) {
    if (interrupt_requested.load()) return false;
    if (!progress) progress.emplace(quiet, static_cast<std::int64_t>(total), 0, "periodic", "starts");
    progress->update(static_cast<std::int64_t>(done), 0);
    return true;
  };
}

/// After a signal: the families of the starts finished before it (not the manifolds) in
/// <out>.partial, the HDF5 file alone, its status saying how many starts it holds.
int write_interrupted(const PeriodicOptions& o, const system::Scene& scene, const PeriodicFlow& body,
                      const PeriodicResult& result) {
  const std::string partial = o.out + ".partial";
  auto parameters = periodic_parameters(o, scene, result.l, result.failures);
  const std::string kept = std::to_string(result.starts_kept) + " of " + std::to_string(result.starts) + " starts";
  parameters["status"] = "interrupted by signal: the families of " + kept +
                         (!result.stopped && o.manifolds > 0 ? "; no manifolds" : "");
  write_groups_file(partial, true, {{"periodic", periodic_columns(body, result.rows, result.section), {}}}, parameters);
  std::cerr << "lgi: periodic: interrupted by signal; the families of " << kept << " (" << result.rows.size()
            << " orbits) are in " << partial << '\n';
  return interrupted_exit_status();
}

/// A Cardan top whose outer angle is cyclic (tilt 0, or no gravity): else no
/// momentum to reduce at (exit 2, naming suspension.tilt); and only the starts it has.
system::CardanTop cardan_top_for_periodic(const PeriodicOptions& o, const system::Scene& scene) {
  system::CardanTop top = cardan_top(scene);
  if (const std::string why = cardan_tilt_refusal(top, scene.file); !why.empty()) throw UsageError("--scene: " + why);
  if (!o.critical.empty()) throw UsageError("--from-critical: a Kovalevskaya top only, not the Cardan top " + scene.file);
  return top;
}

int run_periodic(const PeriodicOptions& o) {
  check_flags(o);
  hdf5::check_output_target(o.out, o.force);  // before the work, not after it
  const bool in_l = o.continue_in == "l";
  const auto [p_min, p_max] = bounds(in_l ? o.l_range : o.h_range, in_l ? "--l-range" : "--h-range");
  const system::Scene scene = read_scene(o.scene);
  std::optional<system::CardanTop> top;
  if (scene.suspension) top = cardan_top_for_periodic(o, scene);
  const PeriodicFlow body = top ? PeriodicFlow(*top) : PeriodicFlow(equilibria_body(scene));
  PeriodicRequest req;
  FamilySettings& s = req.settings;
  s.shooting.dt = o.dt, s.shooting.in_l = in_l, s.shooting.shooting_points = o.shooting_points;
  s.amplitude = o.amplitude, s.steps = o.steps;
  s.h_step = in_l ? std::abs(o.l_step) : o.h_step;
  s.start_h_step = o.h_step;
  s.h_min = p_min, s.h_max = p_max;
  s.locate_events = !o.no_events, s.switch_branches = !o.no_branch_switching;
  req.direction = in_l && o.l_step < 0.0 ? -1.0 : 1.0;
  req.l = o.l, req.from_equilibria = o.from_equilibria;
  req.critical = o.critical, req.scene_file = scene.file;
  if (!o.seed_file.empty()) req.seeds = read_seeds(o.seed_file);
  req.poincare = o.poincare, req.poincare_rows = o.poincare_rows, req.poincare_points = o.poincare_points;
  req.returns = o.returns;
  req.manifolds.points = o.manifolds, req.manifolds.periods = o.manifold_periods;
  req.manifolds.epsilon = o.manifold_epsilon, req.manifolds.dt = o.dt;
  // Progress on stderr (cli/sweep_progress.hpp; issue 50, item 8): the starts (an equilibrium's
  // modes or the seeds), each continued with its doubled families. A signal ends the start in
  // progress within a step of its shooting (euler_poisson_flow.hpp, shoot); that start is dropped
  // and the families of the starts before it go to <out>.partial.
  const InterruptGuard interrupt_guard;
  std::optional<SweepProgress> progress;
  req.start_done = progress_of_starts(progress, o.quiet);
  const PeriodicResult result = periodic_families(body, req);
  if (progress) progress->finish();
  if (interrupt_signal() != 0) return write_interrupted(o, scene, body, result);
  const std::vector<FamilyOrbit>& rows = result.rows;
  const std::vector<std::string>& failures = result.failures;
  const std::vector<RowManifolds>& manifolds = result.manifolds;
  const double l = result.l;
  std::vector<TableGroup> extra;
  if (o.manifolds > 0) extra.push_back(manifold_group(body, manifolds));
  write_table_file(o.out, o.force, "periodic", periodic_columns(body, rows, result.section),
                   periodic_parameters(o, scene, l, failures), extra);
  // Starts that failed are said even with --quiet: they are missing families.
  for (const std::string& f : failures) std::cerr << "lgi: periodic: no family from " << f << '\n';
  if (o.quiet) return exit_ok;
  int degenerate = 0;
  for (const auto& r : rows) {
    std::printf("family=%d index=%d l=%.12g h=%.12g period=%.12g residual=%.2e%s stability=%s%s%s%s\n", r.family,
                r.index, r.orbit.l, r.orbit.h, r.orbit.period, r.orbit.residual,
                top ? (" drift=" + format_general(r.orbit.drift, 9)).c_str() : "", r.orbit.stability.c_str(),
                r.orbit.degenerate ? " degenerate" : "", r.event == "none" ? "" : " event=", r.event == "none" ? "" : r.event.c_str());
    degenerate += r.orbit.degenerate ? 1 : 0;
    if (!r.family_end.empty()) std::printf("family=%d ended: %s\n", r.family, r.family_end.c_str());
  }
  if (degenerate)
    std::printf("note: %d orbit(s) degenerate: the Newton system is rank-deficient and all multipliers are at 1; "
                "they lie on resonant tori (an integrable top) and are not isolated\n", degenerate);
  if (const std::string k = top ? "" : appelrot_summary(body.body, rows); !k.empty()) std::printf("%s\n", k.c_str());
  for (const RowManifolds& m : manifolds)
    std::printf("manifolds of family=%d: multiplier %.9g, %d crossings a period, %zu section points\n", m.family,
                m.m.lambda, m.m.returns, m.m.points.size());
  std::cout << rows.size() << " orbits; wrote " << o.out << '\n';
  return exit_ok;
}

}  // namespace

Subcommand add_periodic_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<PeriodicOptions>();
  auto* sub = app.add_subcommand("periodic",
                                 "Periodic orbits of a heavy top (or of a Cardan top at fixed p1): Lyapunov families from the stable relative "
                                 "equilibria, from seeds or from points of a Poincare section, their Floquet multipliers "
                                 "and stability, continued in h or in l, and the manifolds of hyperbolic orbits "
                                 "(experiments/PERIODIC.md)");
  sub->add_option("--scene", o->scene, "Scene file (TOML): a heavy top, or a Cardan top with a vertical outer axis (reduced at p1 = l)")->required();
  sub->add_option("--l", o->l, "The momentum l = Pi.Gamma (with --seeds-from-poincare: the file's, may be left out)");
  sub->add_flag("--from-equilibria", o->from_equilibria, "The Lyapunov families of every linearly stable equilibrium");
  sub->add_option("--seed-file", o->seed_file, "Seeds, one per line: Pi1 Pi2 Pi3 Gamma1 Gamma2 Gamma3 T (a Cardan top: q1 q2 q3 p1 p2 p3 T)");
  sub->add_option("--from-critical", o->critical,
                  "H1,H2,...: a Kovalevskaya top's critical periodic orbits at these energies (one per critical value)");
  sub->add_option("--seeds-from-poincare", o->poincare,
                  "A file of lgi poincare: seeds on its section at its (l, h) (--poincare-rows, --poincare-point)");
  sub->add_option("--poincare-rows", o->poincare_rows, "Rows of its /events (from 0), comma-separated");
  sub->add_option("--poincare-point", o->poincare_points,
                  "phi,theta,sheet[,N]: a point of its Richter section (a Cardan top: x,y,piece of its section), N its "
                  "own --returns (repeatable)");
  sub->add_option("--returns", o->returns, "The period guess of a section seed: the time of its N-th return")
      ->capture_default_str();
  sub->add_option("--continue-in", o->continue_in, "h (at fixed l) or l (at fixed h; seeds only)")->capture_default_str();
  sub->add_option("--h-range", o->h_range, "A:B: a family stops when h leaves [A, B]");
  sub->add_option("--l-range", o->l_range, "A:B: with --continue-in l, a family stops when l leaves [A, B]");
  sub->add_option("--l-step", o->l_step, "With --continue-in l: the first step in l (its sign the direction)")
      ->capture_default_str();
  sub->add_option("--manifolds", o->manifolds,
                  "N > 0: the stable and unstable manifolds of each hyperbolic first orbit on the section, N points "
                  "a fundamental domain (--seeds-from-poincare)");
  sub->add_option("--manifold-periods", o->manifold_periods, "Integrate the manifold points for this many periods")
      ->capture_default_str();
  sub->add_option("--manifold-epsilon", o->manifold_epsilon, "The fundamental domain's inner end, relative to |x0|")
      ->capture_default_str();
  sub->add_option("--steps", o->steps, "Continuation steps after each family's first orbit")->capture_default_str();
  sub->add_option("--h-step", o->h_step, "The first continuation step in h; later steps keep its arclength (halved on failure)")
      ->capture_default_str();
  sub->add_flag("--no-events", o->no_events, "Do not locate folds, period doublings and class changes");
  sub->add_flag("--switch-branches", o->switch_branches,
                "Start and continue the period-doubled family at each period doubling (the default)");
  sub->add_flag("--no-branch-switching", o->no_branch_switching, "Do not start the doubled family at a period doubling");
  sub->add_option("--shooting-points", o->shooting_points,
                  "M: segments of multiple shooting (1: single shooting); the monodromy is the product of theirs")
      ->capture_default_str();
  sub->add_option("--dt", o->dt, "Step bound of the shooting integrator")->capture_default_str();
  sub->add_option("--amplitude", o->amplitude, "Start amplitude relative to |x_e| (--from-equilibria)")
      ->capture_default_str();
  sub->add_option("--out", o->out, "Output file (HDF5); the same table as CSV beside it")->required();
  add_force_quiet_flags(*sub, *o, "Replace existing output files");
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_periodic(*o);
          },
          [o] { check_flags(*o); }};
}

}  // namespace lgi::experiments
