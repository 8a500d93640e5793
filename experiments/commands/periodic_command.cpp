// lgi periodic --scene FILE --l L (--from-equilibria | --seed-file F) [--h-range A:B] [--steps N]
//              [--h-step D] [--dt DT] [--amplitude E] --out FILE.h5 [--force] [--quiet]
// Periodic orbits of a heavy top's Euler–Poisson flow at fixed ℓ: the Lyapunov
// centre families of the linearly stable relative equilibria, or families from
// seeds, continued in h (analysis/periodic/; layout and method: experiments/PERIODIC.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "experiments/analysis/periodic/lyapunov_families.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/commands/atlas/atlas_tables.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/table_file.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

struct PeriodicOptions {
  std::string scene, out, seed_file, h_range;
  std::optional<double> l;
  bool from_equilibria = false, no_events = false, no_branch_switching = false;
  int steps = 10;
  double h_step = 0.01, dt = 2e-3, amplitude = 1e-4;
  bool force = false, quiet = false;
  std::string command_line;
};

void check_flags(const PeriodicOptions& o) {
  if (!o.l || !std::isfinite(*o.l)) throw UsageError("--l: must be a finite number");
  if (o.from_equilibria == !o.seed_file.empty())
    throw UsageError("--from-equilibria / --seed-file: give exactly one of them");
  if (o.steps < 0 || o.steps > 100000) throw UsageError("--steps: must be in [0, 100000]");
  if (!(o.h_step > 0.0) || !std::isfinite(o.h_step)) throw UsageError("--h-step: must be a positive number");
  if (!(o.dt > 0.0) || !(o.dt <= 1.0)) throw UsageError("--dt: must be in (0, 1]");
  if (!(o.amplitude > 0.0) || !(o.amplitude <= 0.1)) throw UsageError("--amplitude: must be in (0, 0.1]");
}

/// --h-range A:B, A < B.
std::pair<double, double> h_bounds(const std::string& text) {
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
    throw UsageError("--h-range: expected A:B (two numbers), got '" + text + "'");
  }
  if (!(a < b) || !std::isfinite(a) || !std::isfinite(b)) throw UsageError("--h-range: need finite A < B");
  return {a, b};
}

/// Seeds: one per line, Pi1 Pi2 Pi3 Gamma1 Gamma2 Gamma3 T (spaces or commas; '#' starts a comment).
std::vector<std::pair<Vec6, double>> read_seeds(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw UsageError("--seed-file: cannot read '" + path + "'");
  std::vector<std::pair<Vec6, double>> seeds;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = line.substr(0, line.find('#'));
    for (char& c : line) c = c == ',' ? ' ' : c;
    std::istringstream s(line);
    std::vector<double> v;
    double d = 0.0;
    while (s >> d) v.push_back(d);
    if (v.empty() && (s.eof() || line.find_first_not_of(" \t\r") == std::string::npos)) continue;
    Vec6 x;
    bool finite = v.size() == 7 && s.eof();
    for (std::size_t k = 0; finite && k < 6; ++k) x(static_cast<int>(k)) = v[k], finite = std::isfinite(v[k]);
    if (!finite || !(v[6] > 0.0) || !std::isfinite(v[6]) || x.tail<3>().norm() == 0.0)
      throw UsageError("--seed-file: " + path + " line " + std::to_string(n) +
                       ": expected Pi1 Pi2 Pi3 Gamma1 Gamma2 Gamma3 T (Gamma nonzero, T > 0)");
    seeds.emplace_back(x, v[6]);
  }
  if (seeds.empty()) throw UsageError("--seed-file: " + path + " holds no seed");
  return seeds;
}

std::vector<TableColumn> periodic_columns(const std::vector<FamilyOrbit>& rows) {
  std::vector<TableColumn> c = {{"family", 1, true}, {"index", 1, true}, {"l"}, {"h"}, {"period"},
                                {"angular_momentum", 3}, {"gamma", 3}, {"residual"}, {"multipliers", 12},
                                {"stability", 1, false, {}, {}, {}, true}, {"event", 1, false, {}, {}, {}, true},
                                {"degenerate", 1, true}, {"equilibrium", 1, true}, {"omega"},
                                {"trivial_deviation"}, {"product_deviation"}, {"parent", 1, true},
                                {"reduced_trace"}, {"invariance_defect"},
                                {"family_end", 1, false, {}, {}, {}, true}};
  for (const auto& r : rows) {
    const PeriodicOrbit& o = r.orbit;
    c[0].whole.push_back(r.family), c[1].whole.push_back(r.index);
    c[2].real.push_back(o.l), c[3].real.push_back(o.h), c[4].real.push_back(o.period);
    for (int k = 0; k < 3; ++k) c[5].real.push_back(o.x0(k)), c[6].real.push_back(o.x0(k + 3));
    c[7].real.push_back(o.residual);
    for (const auto& m : o.multipliers) c[8].real.push_back(m.real()), c[8].real.push_back(m.imag());
    c[9].text.push_back(o.stability), c[10].text.push_back(r.event);
    c[11].whole.push_back(o.degenerate ? 1 : 0), c[12].whole.push_back(r.equilibrium);
    c[13].real.push_back(r.omega), c[14].real.push_back(o.trivial_deviation), c[15].real.push_back(o.product_deviation);
    c[16].whole.push_back(r.parent), c[17].real.push_back(o.reduced_trace), c[18].real.push_back(o.invariance_defect);
    c[19].text.push_back(r.family_end);
  }
  return c;
}

std::string failures_text(const std::vector<std::string>& failures) {
  std::string t = failures.empty() ? "none" : "";
  for (const std::string& f : failures) t += (t.empty() ? "" : "; ") + f;
  return t;
}

int run_periodic(const PeriodicOptions& o) {
  check_flags(o);
  const auto [h_min, h_max] = h_bounds(o.h_range);
  const system::Scene scene = read_scene(o.scene);
  if (scene.suspension) throw UsageError("--scene: " + scene.file + " is a Cardan top; lgi periodic takes a heavy top");
  const HeavyTopBody body = equilibria_body(scene);
  FamilySettings s;
  s.shooting.dt = o.dt, s.amplitude = o.amplitude, s.steps = o.steps, s.h_step = o.h_step;
  s.h_min = h_min, s.h_max = h_max;
  s.locate_events = !o.no_events, s.switch_branches = !o.no_branch_switching;
  std::vector<FamilyOrbit> rows;
  std::vector<std::string> failures;
  if (o.from_equilibria) {
    rows = lyapunov_families(body, *o.l, s, failures);
  } else {
    int family = 0;
    for (const auto& [x, T] : read_seeds(o.seed_file)) {
      const double h = euler_poisson_invariants(body, x).value(0);
      const auto f = continue_family(body, x, T, h, *o.l, 1.0, family, s, failures);
      for (const auto& r : f) family = std::max(family, r.family + 1);
      rows.insert(rows.end(), f.begin(), f.end());
    }
  }
  write_table_file(o.out, o.force, "periodic", periodic_columns(rows),
                   {{"subcommand", "periodic"}, {"command_line", o.command_line}, {"scene_file", scene.file},
                    {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version},
                    {"l", format_general(*o.l, 17)}, {"dt", format_general(o.dt, 17)},
                    {"integrator", "implicit midpoint, triple jump twice (order 6), ceil(T/dt) equal steps"},
                    {"continuation", "pseudo-arclength in (x0, T, h) after a first natural step in h"},
                    {"events", o.no_events ? "not located" : "fold, period_doubling, class_change (tr P = +-2)"},
                    {"branch_switching", o.no_branch_switching || o.no_events ? "no" : "at period doublings"},
                    {"failures", failures_text(failures)}});
  // Starts that failed are said even with --quiet: they are missing families.
  for (const std::string& f : failures) std::cerr << "lgi: periodic: no family from " << f << '\n';
  if (o.quiet) return exit_ok;
  int degenerate = 0;
  for (const auto& r : rows) {
    std::printf("family=%d index=%d h=%.12g period=%.12g residual=%.2e stability=%s%s%s%s\n", r.family, r.index,
                r.orbit.h, r.orbit.period, r.orbit.residual, r.orbit.stability.c_str(),
                r.orbit.degenerate ? " degenerate" : "", r.event == "none" ? "" : " event=", r.event == "none" ? "" : r.event.c_str());
    degenerate += r.orbit.degenerate ? 1 : 0;
    if (!r.family_end.empty()) std::printf("family=%d ended: %s\n", r.family, r.family_end.c_str());
  }
  if (degenerate)
    std::printf("note: %d orbit(s) degenerate: the Newton system is rank-deficient and all multipliers are at 1; "
                "they lie on resonant tori (an integrable top) and are not isolated\n", degenerate);
  std::cout << rows.size() << " orbits; wrote " << o.out << '\n';
  return exit_ok;
}

}  // namespace

Subcommand add_periodic_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<PeriodicOptions>();
  auto* sub = app.add_subcommand("periodic",
                                 "Periodic orbits of a heavy top at fixed l: Lyapunov families from the stable relative "
                                 "equilibria or from seeds, their Floquet multipliers and stability, continued in h "
                                 "(experiments/PERIODIC.md)");
  sub->add_option("--scene", o->scene, "Scene file (TOML): a heavy top")->required();
  sub->add_option("--l", o->l, "The momentum l = Pi.Gamma")->required();
  sub->add_flag("--from-equilibria", o->from_equilibria, "The Lyapunov families of every linearly stable equilibrium");
  sub->add_option("--seed-file", o->seed_file, "Seeds, one per line: Pi1 Pi2 Pi3 Gamma1 Gamma2 Gamma3 T");
  sub->add_option("--h-range", o->h_range, "A:B: a family stops when h leaves [A, B]");
  sub->add_option("--steps", o->steps, "Continuation steps after each family's first orbit")->capture_default_str();
  sub->add_option("--h-step", o->h_step, "The first continuation step in h; later steps keep its arclength (halved on failure)")
      ->capture_default_str();
  sub->add_flag("--no-events", o->no_events, "Do not locate folds, period doublings and class changes");
  sub->add_flag("--no-branch-switching", o->no_branch_switching, "Do not start the doubled family at a period doubling");
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
