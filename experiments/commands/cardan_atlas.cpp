// The Cardan half of lgi equilibria, lgi bifurcation and lgi poincare
// (docs/cardan.md §9; analysis/cardan_equilibria.hpp, analysis/cardan_section.hpp).
#include "experiments/commands/cardan_atlas.hpp"

#include <omp.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "experiments/analysis/cardan_equilibria.hpp"
#include "experiments/analysis/cardan_section.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/commands/atlas/atlas_tables.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "lgi/build_info.hpp"
#include "lie/quaternion.hpp"

namespace lgi::experiments {
namespace {

std::map<std::string, std::string> provenance(const system::Scene& scene, const std::string& subcommand,
                                              const std::string& command_line) {
  return {{"subcommand", subcommand},        {"system", "cardan (T^3)"},
          {"command_line", command_line},    {"scene_file", scene.file},
          {"scene_toml", scene.toml_text},   {"lgi_version", build_info::version},
          {"compiler", build_info::compiler}, {"cxx_flags", build_info::cxx_flags}};
}

void push3(std::vector<double>& v, const Vec3& x) { v.insert(v.end(), x.data(), x.data() + 3); }

std::vector<TableColumn> equilibrium_columns(const std::vector<CardanEquilibrium>& rows) {
  std::vector<TableColumn> c = shared_equilibrium_columns();
  c.insert(c.end(), {{"cardan_angles", 3}, {"degenerate", 1, true}, {"pole", 1, true}});
  for (const auto& e : rows) {
    push_shared_equilibrium_row(c, e, false);  // no folds are located on a Cardan top's branches
    push3(c[12].real, e.q);
    c[13].whole.push_back(e.degenerate ? 1 : 0);
    c[14].whole.push_back(e.pole ? 1 : 0);
  }
  return c;
}

}  // namespace

int run_cardan_equilibria(const system::Scene& scene, const CardanEquilibriaRequest& r) {
  const system::CardanTop top = cardan_top(scene);
  require_cyclic_outer_angle(top, scene.file, r.subcommand);
  if (r.omega_max && !(*r.omega_max > 0.0)) throw UsageError("--omega-max: must be a positive number");
  const double omega_max = r.omega_max.value_or(default_cardan_omega_max(top));
  if (!r.l) hdf5::check_output_target(r.out, r.force);  // before the work, not after it
  // Signals only set the flag until the file is written (interrupt_guard.hpp). Without --l a
  // progress line counts the values of omega, as the heavy top's counts its branches
  // (cli/sweep_progress.hpp); a signal stops after the current omega and nothing is written.
  const InterruptGuard interrupt_guard;
  std::optional<SweepProgress> progress;
  const auto sample_done = [&](std::size_t done, std::size_t total) {
    if (interrupt_requested.load()) return false;
    if (!progress) progress.emplace(r.quiet, static_cast<std::int64_t>(total), 0, r.subcommand.c_str(), "values of omega");
    progress->update(static_cast<std::int64_t>(done), 0);
    return true;
  };
  const std::vector<CardanEquilibrium> rows =
      r.l ? cardan_equilibria_at(top, *r.l) : cardan_equilibrium_branches(top, r.samples, omega_max, 64, sample_done);
  if (progress) progress->finish();
  if (interrupt_signal() != 0) {
    std::cerr << "lgi: " << r.subcommand << ": interrupted by signal; nothing written\n";
    return interrupted_exit_status();
  }
  auto parameters = provenance(scene, r.subcommand, r.command_line);
  if (r.l) parameters["l"] = format_general(*r.l, 17);
  else parameters["omega_max"] = format_general(omega_max, 17);
  parameters["branches"] = "Cardan top: critical points of the amended potential U_l (with --l) or of the augmented "
                           "potential W_omega (without), docs/cardan.md section 9";
  write_table_file(r.out, r.force, "equilibria", equilibrium_columns(rows), parameters);
  if (r.quiet) return exit_ok;
  if (r.l)
    for (const auto& e : rows)
      std::printf("q2=%.6g q3=%.6g omega=%.6g l=%.6g h=%.6g stability=%s g1=%.6g g2=%.6g nonlinearly_stable=%s%s%s\n",
                  e.q(1), e.q(2), e.omega, e.l, e.h, stability_name(e.stability), e.g1, e.g2,
                  e.nonlinearly_stable ? "yes" : "no", e.degenerate ? " degenerate" : "", e.pole ? " pole" : "");
  else
    std::cout << rows.size() << " points of the Cardan top's branches (omega in +-" << format_general(omega_max, 6)
              << "); wrote " << r.out << '\n';
  return exit_ok;
}

namespace {

struct OrbitTable {
  std::vector<TableColumn> sweep = {
      {"index", 1, true}, {"status", 1, true}, {"steps", 1, true}, {"cpu_seconds"},
      {"initial_cardan_angles", 3}, {"initial_cardan_momenta", 3}, {"cardan_angles", 3}, {"cardan_momenta", 3},
      {"angular_momentum", 3}, {"orientation", 4}, {"max_energy_error"}, {"max_cardan_momentum_1_error"},
      {"crossings", 1, true}};
  std::vector<TableColumn> events = {{"index", 1, true}, {"t"}, {"cardan_angles", 3}, {"cardan_momenta", 3},
                                     {"angular_momentum", 3}, {"orientation", 4}, {"gamma", 3},
                                     {"piece", 1, true}, {"x"}, {"y"}, {"direction", 1, true}};
  std::string reasons;
};

void push_body(const system::CardanTop& top, const system::TorusState& x, std::vector<double>& Pi,
               std::vector<double>& quaternion) {
  const lie::SO3xR3 b = top.body_state(x);
  push3(Pi, b.Pi);
  const auto w = lie::to_wxyz(lie::quat_from_matrix(b.R));
  quaternion.insert(quaternion.end(), w.begin(), w.end());
}

void add_orbit(OrbitTable& t, const system::CardanTop& top, std::int64_t i, const CardanOrbit& o) {
  auto& s = t.sweep;
  s[0].whole.push_back(i), s[1].whole.push_back(o.status), s[2].whole.push_back(o.steps);
  s[3].real.push_back(o.cpu_seconds);
  push3(s[4].real, o.initial.q), push3(s[5].real, o.initial.p), push3(s[6].real, o.final.q), push3(s[7].real, o.final.p);
  push_body(top, o.final, s[8].real, s[9].real);
  // p1 is an integral only where q1 is cyclic (docs/cardan.md §3): elsewhere its change is no error.
  s[10].real.push_back(o.max_energy_error);
  s[11].real.push_back(top.outer_angle_cyclic() ? o.max_momentum_error : std::nan(""));
  s[12].whole.push_back(static_cast<std::int64_t>(o.crossings.size()));
  if (o.status != 0) t.reasons += std::to_string(i) + ": " + o.reason + "\n";
  auto& e = t.events;
  for (const CardanCrossing& c : o.crossings) {
    e[0].whole.push_back(i), e[1].real.push_back(c.t);
    push3(e[2].real, c.x.q), push3(e[3].real, c.x.p);
    push_body(top, c.x, e[4].real, e[5].real);
    push3(e[6].real, top.attitude(c.x.q).transpose() * Vec3::UnitZ());
    e[7].whole.push_back(c.piece), e[8].real.push_back(c.x_coord), e[9].real.push_back(c.y_coord);
    e[10].whole.push_back(c.direction);
  }
}

void check_poincare_request(const system::CardanTop& top, const system::Scene& scene, const CardanPoincareRequest& r) {
  check_cardan_section_scheme(r.scheme);
  if (!(r.dt > 0.0)) throw UsageError("--dt: missing, and the scene " + scene.file + " has no [run] dt");
  if (!top.outer_angle_cyclic()) return;  // the slice q1 = 0 of a tilted frame: no reduced level set to check
  const double lowest = cardan_minimum_energy(top, r.l);
  if (r.h < lowest - 1e-12 * std::max(1.0, std::abs(lowest)))
    throw UsageError("--h: h is below the minimum energy at this l: h = " + format_general(r.h, 17) + " < " +
                     format_general(lowest, 17) + " = min H at l = " + format_general(r.l, 17) + " for " + scene.file +
                     " (the level set is empty)");
}

}  // namespace

int run_cardan_poincare(const system::Scene& scene, const CardanPoincareRequest& r) {
  const system::CardanTop top = cardan_top(scene);
  check_poincare_request(top, scene, r);
  const bool p1_conserved = top.outer_angle_cyclic();
  if (!p1_conserved)
    std::cerr << "lgi: warning: --l: p1 is no integral of " << scene.file << " (tilted outer axis with gravity): --l "
              << "sets each orbit's initial p1 only, and the section is a projection (docs/cardan.md section 9.3)\n";
  CardanOrbitRequest request{r.scheme, r.t_end, r.dt, r.max_events, r.lyapunov || r.megno, r.seed, &interrupt_requested};
  std::vector<CardanOrbit> orbits(static_cast<std::size_t>(r.ics));
  std::vector<char> done(orbits.size(), 0);
  // Signals only set the flag from before the first file exists until the results are published (interrupt_guard.hpp).
  const InterruptGuard interrupt_guard;
  {
#pragma omp parallel for schedule(dynamic, 1) num_threads(r.threads)
    for (std::int64_t i = 0; i < r.ics; ++i) {
      if (interrupt_requested.load(std::memory_order_relaxed)) continue;
      CardanOrbit& o = orbits[static_cast<std::size_t>(i)];
      system::TorusState x0;
      if (draw_cardan_level_point(top, r.l, r.h, r.seed, i, x0)) o = cardan_orbit(top, x0, request, i);
      else o.status = 2, o.reason = "no initial state on the level set at q1 = 0 in 100000 draws";
      // An orbit the signal may have cut short (the orbit and its indicators read the flag) is not kept.
      done[static_cast<std::size_t>(i)] = interrupt_requested.load() ? 0 : 1;
    }
  }
  OrbitTable table;
  std::vector<double> lyapunov, megno;
  std::int64_t finished = 0, crossings = 0, failed = 0;
  for (std::int64_t i = 0; i < r.ics; ++i) {
    if (!done[static_cast<std::size_t>(i)]) continue;
    const CardanOrbit& o = orbits[static_cast<std::size_t>(i)];
    add_orbit(table, top, i, o);
    lyapunov.push_back(o.lyapunov), megno.push_back(o.megno);
    ++finished, crossings += static_cast<std::int64_t>(o.crossings.size()), failed += o.status != 0;
  }
  if (r.lyapunov) table.sweep.push_back({"lyapunov", 1, false, lyapunov});
  if (r.megno) table.sweep.push_back({"megno", 1, false, megno});
  auto parameters = provenance(scene, "poincare", r.command_line);
  parameters["scheme"] = r.scheme;
  parameters["section"] = "S = -sin(q2) dq2/dt = 0 (docs/cardan.md section 9)";
  for (const auto& [k, v] : std::map<std::string, double>{{"l", r.l}, {"h", r.h}, {"t_end", r.t_end}, {"dt", r.dt}})
    parameters[k] = format_general(v, 17);
  parameters["seed"] = std::to_string(r.seed);
  parameters["p1_conserved"] = p1_conserved ? "yes" : "no";
  parameters["failed_orbits"] = table.reasons;
  const bool interrupted = finished < r.ics;
  parameters["status"] = interrupted ? "interrupted by signal: " + std::to_string(finished) + " of " +
                                           std::to_string(r.ics) + " orbits"
                                     : "complete";
  const std::string path = interrupted ? r.out + ".partial" : r.out;
  write_groups_file(path, r.force || interrupted, {{"sweep", table.sweep}, {"events", table.events}}, parameters);
  if (interrupted) {
    std::cerr << "lgi: poincare interrupted by signal; the " << finished << " completed orbits are in " << path << '\n';
    return interrupted_exit_status();
  }
  if (!r.quiet)
    std::cout << "poincare: " << r.ics << " orbits of " << r.scheme << " on the Cardan top " << scene.file
              << (p1_conserved ? " at l = " : " at initial p1 = ") << format_general(r.l, 6)
              << ", h = " << format_general(r.h, 6) << ", " << failed
              << " failed, " << crossings << " crossings; wrote " << r.out << '\n';
  return exit_ok;
}

}  // namespace lgi::experiments
