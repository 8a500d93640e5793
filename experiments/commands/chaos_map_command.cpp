// lgi chaos-map --scene FILE --l-range a:b:n --h-range a:b:n --ics N --t-end T [--dt H] [--seed S]
//   [--measure liouville|uniform] [--threshold Y] [--threads N] [--out FILE.h5] [--force] [--quiet]
// lgi chaos-map --scene CARDAN.toml --vary KEY=a:b:n --h-range ... [--resume]: a Cardan top's
//   (KEY, h) plane (chaos_map/cardan_chaos_map.hpp).
// The fraction of chaotic orbits over the (l, h) plane of a heavy top: in
// every cell N initial states drawn on the level set (l, h) exactly as
// `lgi poincare --l --h --ics N --seed S` draws them, and for each the MEGNO
// and the maximal Lyapunov exponent from the tangent flow
// (analysis/poincare_section.hpp, orbit_indicators); an orbit is chaotic
// where MEGNO <Y>(t_end) > threshold, and the chaotic fraction is given with
// its 95 % Wilson interval (layout and meaning: experiments/CHAOS_MAP.md).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "experiments/analysis/accessible_region.hpp"
#include "experiments/analysis/poincare_section.hpp"
#include "experiments/analysis/sweep_plan.hpp"
#include "experiments/cli/work_limits.hpp"
#include "experiments/cli/thread_count.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/commands/chaos_map/cardan_chaos_map.hpp"
#include "experiments/commands/chaos_map/chaos_map_cells.hpp"
#include "experiments/cli/grid_range.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/commands/sweep/sweep_ranks.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/sweep_spec.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "integrators/ensemble/tangent_ensemble.hpp"
#include "integrators/core/loop_support.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

struct ChaosMapOptions {
  std::string scene, out, l_range, h_range, measure = "liouville", vary;
  std::int64_t ics = 0;
  double t_end = 0.0, threshold = 3.0;
  std::optional<double> dt;
  std::uint64_t seed = 0;
  int threads = 0;
  bool force = false, quiet = false, resume = false;
  std::string command_line;
};

using CellStatus = ChaosCellStatus;

std::string number(double x) { return exact_number(x); }

void check_flags(const ChaosMapOptions& o) {
  if (o.l_range.empty() == o.vary.empty())
    throw UsageError(o.vary.empty() ? "--l-range: missing: give --l-range (a heavy top's (l, h) plane) or --vary "
                                      "KEY=a:b:n (a Cardan top's (KEY, h) plane)"
                                    : "--vary: replaces --l-range (a Cardan top's (KEY, h) plane): give one of them");
  const std::size_t axis = o.vary.empty() ? parse_grid_range(o.l_range, "--l-range").size()
                                          : parse_vary_flag(o.vary).values.size();
  const auto cells = static_cast<std::int64_t>(axis * parse_grid_range(o.h_range, "--h-range").size());
  check_work_limit(o.vary.empty() ? "--l-range" : "--vary", cells, max_grid_cells,
                   o.vary.empty() ? "cells (--l-range x --h-range)" : "cells (--vary x --h-range)");
  if (o.ics < 1 || o.ics > 1000000) throw UsageError("--ics: must be between 1 and 1000000");
  check_work_limit("--ics", saturating_product(cells, o.ics), max_orbits, "orbits (cells x --ics)");
  if (!(o.t_end > 0.0) || !std::isfinite(o.t_end)) throw UsageError("--t-end: must be a positive number");
  if (o.dt && (!(*o.dt > 0.0) || !std::isfinite(*o.dt))) throw UsageError("--dt: must be a positive number");
  if (!std::isfinite(o.threshold)) throw UsageError("--threshold: must be a finite number");
  if (o.seed > static_cast<std::uint64_t>(INT64_MAX)) throw UsageError("--seed: at most 2^63 - 1 (a TOML integer)");
  if (!level_measure_from_name(o.measure))
    throw UsageError("--measure: \"" + o.measure + "\": expected liouville or uniform");
}

/// The level-set draw of `lgi poincare` at (l, h): the same spec keys, so the
/// same initial states for the same seed (experiments/SWEEPS.md, "Level set").
std::string spec_text(const ChaosMapOptions& o, const std::string& scene_path, double dt, double l, double h) {
  return "name = \"lgi chaos-map\"\nscene = \"" + scene_path + "\"\nscheme = \"rkmk4\"\ndt = " + number(dt) +
         "\nt_end = " + number(o.t_end) + "\nseed = " + std::to_string(o.seed) + "\nsamples = " + std::to_string(o.ics) +
         "\n\n[level_set]\nh = " + number(h) + "\nl = " + number(l) + "\nmeasure = \"" + o.measure + "\"\n";
}

/// One cell: its spec and plan (none where the level is empty or not reached).
struct Cell {
  double l = 0.0, h = 0.0;
  CellStatus status = cell_ok;
  std::unique_ptr<SweepSpec> spec;
  std::unique_ptr<SweepPlan> plan;
};

struct Orbit {
  double megno = NAN, lyapunov = NAN;
  Vec3 gamma = Vec3::Constant(NAN), Pi = Vec3::Constant(NAN);
  bool done = false;
};

std::vector<Cell> make_cells(const ChaosMapOptions& o, const system::Scene& scene, const HeavyTopBody& body, double dt,
                             const std::vector<double>& ls, const std::vector<double>& hs, std::vector<double>& h_min) {
  const std::string scene_path = std::filesystem::absolute(o.scene).lexically_normal().string();
  std::vector<Cell> cells;
  for (const double l : ls) {
    const double lowest = minimum_energy(body, l);
    h_min.push_back(lowest);
    for (const double h : hs) {
      Cell c;
      c.l = l, c.h = h;
      if (h < lowest) {
        c.status = cell_empty;
      } else {
        try {
          c.spec = std::make_unique<SweepSpec>(parse_sweep_spec(spec_text(o, scene_path, dt, l, h), "lgi-chaos-map.toml"));
          c.plan = std::make_unique<SweepPlan>(*c.spec, scene);
        } catch (const InputError&) {  // h within the lattice's resolution of the minimum: no draw
          c.status = cell_unreached;
          c.plan.reset();
        }
      }
      cells.push_back(std::move(c));
    }
  }
  return cells;
}

/// Where the orbits ran: "avx512 (16 lanes)", or "off" and why (the tangent lanes, docs/ensemble.md).
std::string simd_note(const system::Scene& scene) {
  const std::optional<integrators::ensemble::Isa> isa = integrators::ensemble::sweep_isa();
  std::string why;
  if (!integrators::ensemble::ensemble_model(system::make_model(scene), &why)) return "off; " + why;
  if (!isa) return "off";
  return std::string(integrators::ensemble::isa_name(*isa)) + " (" +
         std::to_string(integrators::ensemble::isa_lanes(*isa)) + " lanes)";
}

/// Every orbit of every cell, on `threads` threads (each orbit a function of
/// its cell and index alone); stops early when a signal asks. A task is up to
/// max_lanes orbits of one cell, run together in the SIMD lanes of the tangent
/// flow where the scene has them (orbit_indicators; the same values bit for bit).
std::vector<Orbit> run_orbits(const ChaosMapOptions& o, const std::vector<Cell>& cells, const system::Scene& scene,
                              double dt, int threads) {
  constexpr std::int64_t batch = integrators::ensemble::max_lanes;
  const std::int64_t per_cell = (o.ics + batch - 1) / batch;
  const auto tasks = static_cast<std::int64_t>(cells.size()) * per_cell;
  const auto total = static_cast<std::int64_t>(cells.size()) * o.ics;
  std::vector<Orbit> orbits(static_cast<std::size_t>(total));
  const std::optional<integrators::ensemble::Isa> isa = integrators::ensemble::sweep_isa();
  // Progress on stderr (cli/sweep_progress.hpp): in place on a terminal, else a line every 10 s.
  SweepProgress progress(o.quiet, total, 0, "chaos-map", "orbits");
  std::int64_t finished = 0;
#pragma omp parallel num_threads(threads)
  {
    std::vector<double> flat;
    std::vector<system::State> x0;
    std::vector<std::int64_t> index;
    std::vector<Orbit*> rows;
    std::vector<OrbitIndicators> ind;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t task = 0; task < tasks; ++task) {
      const std::int64_t c = task / per_cell;
      const Cell& cell = cells[static_cast<std::size_t>(c)];
      if (!cell.plan || interrupt_requested) continue;
      x0.clear(), index.clear(), rows.clear();
      const std::int64_t first = (task % per_cell) * batch;
      for (std::int64_t i = first; i < std::min(first + batch, o.ics); ++i) {
        Orbit& r = orbits[static_cast<std::size_t>(c * o.ics + i)];
        try {
          cell.plan->inputs(i, flat);
          const system::State x = cell.plan->initial_state(i, scene, flat);
          r.gamma = x.R.transpose() * Vec3::UnitZ(), r.Pi = x.Pi;
          x0.push_back(x), index.push_back(i), rows.push_back(&r);
        } catch (const std::exception&) {  // no initial state (TrajectorySetupError): NaN indicators
        }
      }
      ind.assign(x0.size(), OrbitIndicators{});
      orbit_indicators(scene, x0, o.t_end, dt, o.seed, index, isa, ind);
      for (std::size_t k = 0; k < rows.size(); ++k) rows[k]->megno = ind[k].megno, rows[k]->lyapunov = ind[k].lyapunov;
      for (std::int64_t i = first; i < std::min(first + batch, o.ics); ++i)
        orbits[static_cast<std::size_t>(c * o.ics + i)].done = !interrupt_requested;
      const std::int64_t count = std::min(first + batch, o.ics) - first;
#pragma omp critical(chaos_map_progress)
      progress.update(finished += count, 0);
    }
  }
  progress.finish();
  return orbits;
}

/// The per-cell summary (/chaos_map) and the per-orbit table (/orbits).
std::vector<TableGroup> result_groups(const ChaosMapOptions& o, const std::vector<Cell>& cells,
                                      const std::vector<Orbit>& orbits, const std::vector<double>& ls,
                                      const std::vector<double>& hs, const std::vector<double>& h_min) {
  const int width = static_cast<int>(hs.size());
  TableColumn l_col{"l"}, h_col{"h"}, h_min_col{"h_min"};
  ChaosCellColumns summary(width);
  l_col.real = ls, h_col.real = hs, h_min_col.real = h_min;
  std::vector<TableColumn> per = {{"l"}, {"h"}, {"cell", 1, true}, {"index", 1, true}, {"megno"}, {"lyapunov"},
                                  {"initial.gamma", 3}, {"initial.angular_momentum", 3}};
  for (std::size_t c = 0; c < cells.size(); ++c) {
    std::vector<double> megno, lyapunov;
    bool complete = true;
    for (std::int64_t i = 0; cells[c].plan && i < o.ics; ++i) {
      const Orbit& r = orbits[c * static_cast<std::size_t>(o.ics) + static_cast<std::size_t>(i)];
      if (!r.done) {
        complete = false;
        continue;
      }
      per[0].real.push_back(cells[c].l), per[1].real.push_back(cells[c].h);
      per[2].whole.push_back(static_cast<std::int64_t>(c)), per[3].whole.push_back(i);
      per[4].real.push_back(r.megno), per[5].real.push_back(r.lyapunov);
      per[6].real.insert(per[6].real.end(), r.gamma.data(), r.gamma.data() + 3);
      per[7].real.insert(per[7].real.end(), r.Pi.data(), r.Pi.data() + 3);
      if (!std::isfinite(r.megno) || !std::isfinite(r.lyapunov)) continue;
      megno.push_back(r.megno), lyapunov.push_back(r.lyapunov);
    }
    summary.add(cells[c].status == cell_ok && !complete ? cell_not_run : cells[c].status, megno, lyapunov, o.threshold);
  }
  TableGroup map{"chaos_map", {l_col, h_col, h_min_col}};
  for (const TableColumn& c : summary.columns()) map.columns.push_back(c);
  add_chaos_map_attributes(map, o.threshold, o.measure, "empty level (h below the minimum energy at l)",
                           "level not reached by the draw (h within 1e-3 of the minimum)");
  return {map, TableGroup{"orbits", per}};
}

/// A Cardan scene: the (key, h) plane (commands/chaos_map/cardan_chaos_map.hpp).
int run_cardan(const ChaosMapOptions& o, const system::Scene& scene, double dt, int threads) {
  if (o.vary.empty())
    throw UsageError("--l-range: " + scene.file + " is a Cardan top: map a (KEY, h) plane with --vary KEY=a:b:n, "
                     "e.g. --vary suspension.tilt=0:1.5707963267948966:8 (docs/cardan.md section 9.4)");
  if (o.measure != "liouville")
    throw UsageError("--measure: a Cardan top's orbits are drawn from the microcanonical (Liouville) measure of "
                     "{H = h} only (docs/cardan.md section 9.4)");
  CardanChaosMapRequest r;
  r.vary = o.vary, r.h_range = o.h_range, r.out = o.out, r.command_line = o.command_line;
  r.ics = o.ics, r.t_end = o.t_end, r.dt = dt, r.threshold = o.threshold, r.seed = o.seed, r.threads = threads;
  r.force = o.force, r.quiet = o.quiet, r.resume = o.resume;
  return run_cardan_chaos_map(scene, r);
}

int run_chaos_map(const ChaosMapOptions& o) {
  check_flags(o);
  const system::Scene scene = read_scene(o.scene);
  const double dt = o.dt ? *o.dt : scene.dt.value_or(0.0);
  if (!(dt > 0.0)) throw UsageError("--dt: missing, and the scene " + scene.file + " has no [run] dt");
  if (const std::string why = integrators::fixed_step_grid_problem(0.0, o.t_end, dt); !why.empty())
    throw UsageError("--dt: " + why);
  const int threads = o.threads > 0 ? o.threads : SweepRanks::world().default_threads();
  if (scene.suspension) return run_cardan(o, scene, dt, threads);
  if (!o.vary.empty())
    throw UsageError("--vary: maps a Cardan scene ([suspension], docs/cardan.md); " + scene.file +
                     " is a heavy top on SO(3): map its (l, h) plane with --l-range");
  if (o.resume) throw UsageError("--resume: only for a Cardan scene's map (--vary) so far");
  if (SweepRanks::world().size() > 1) throw UsageError("lgi chaos-map runs a heavy top's map on one MPI rank (use --threads)");
  const HeavyTopBody body = heavy_top_of(scene, "chaos-map");
  hdf5::check_output_target(o.out, o.force);
  const std::vector<double> ls = parse_grid_range(o.l_range, "--l-range"), hs = parse_grid_range(o.h_range, "--h-range");
  std::vector<double> h_min;
  const std::vector<Cell> cells = make_cells(o, scene, body, dt, ls, hs, h_min);
  const auto start = std::chrono::steady_clock::now();
  // Signals only set the flag from before the first file exists until the results are published (interrupt_guard.hpp).
  const InterruptGuard interrupt_guard;
  const std::vector<Orbit> orbits = run_orbits(o, cells, scene, dt, threads);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const bool interrupted = interrupt_signal() != 0;
  std::map<std::string, std::string> parameters = {
      {"subcommand", "chaos-map"}, {"command_line", o.command_line}, {"scene_file", scene.file},
      {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version}, {"compiler", build_info::compiler},
      {"cxx_flags", build_info::cxx_flags}, {"l_range", o.l_range}, {"h_range", o.h_range},
      {"ics", std::to_string(o.ics)}, {"t_end", number(o.t_end)}, {"dt", number(dt)}, {"seed", std::to_string(o.seed)},
      {"threshold", number(o.threshold)}, {"measure", o.measure}, {"indicators", "RKMK4 on the state and its tangent (integrators/core/tangent_flow.hpp; "
                                                      "integrators/ensemble/tangent_ensemble.hpp)"},
      {"simd", simd_note(scene)},
      {"threads", std::to_string(threads)}, {"wall_seconds", format_general(wall, 6)},
      {"status", interrupted ? "interrupted by signal" : "complete"}};
  const auto groups = result_groups(o, cells, orbits, ls, hs, h_min);
  const std::string path = interrupted ? o.out + ".partial" : o.out;
  write_groups_file(path, o.force || interrupted, groups, parameters);
  if (interrupted) {
    std::cerr << "lgi: chaos-map interrupted by signal; the finished orbits are in " << path << '\n';
    return interrupted_exit_status();
  }
  if (!o.quiet) {
    std::cout << "chaos-map: " << ls.size() << " x " << hs.size() << " cells, " << o.ics << " orbits each (" << o.measure
              << " measure) to t = " << format_general(o.t_end, 6) << ", chaotic where MEGNO > "
              << format_general(o.threshold, 6) << "; "
              << format_general(wall, 3) << " s wall on " << threads << " threads; wrote " << o.out << '\n';
    print_chaos_fractions(groups[0], "l", "l");
  }
  return exit_ok;
}

}  // namespace

Subcommand add_chaos_map_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<ChaosMapOptions>();
  auto* sub = app.add_subcommand(
      "chaos-map",
      "The fraction of chaotic orbits (MEGNO above a threshold), the median MEGNO and the largest Lyapunov "
      "exponent on each cell of an (l, h) grid of a heavy top (experiments/CHAOS_MAP.md)");
  sub->add_option("--scene", o->scene, "Scene file (a heavy top: gravity alone, or a free body; or a Cardan top with --vary)")->required();
  sub->add_option("--l-range", o->l_range, "l values a:b:n (n from a to b); a heavy top's map");
  sub->add_option("--vary", o->vary,
                  "KEY=a:b:n: a Cardan top's map over a scene key (as a sweep spec names it, e.g. suspension.tilt, "
                  "body.center_of_mass_1) instead of l; experiments/CHAOS_MAP.md");
  sub->add_flag("--resume", o->resume, "Go on from <out>.partial (a Cardan map of the same command line)");
  sub->add_option("--h-range", o->h_range, "h values a:b:n")->required();
  sub->add_option("--ics", o->ics, "Orbits per cell, drawn on the level set as lgi poincare draws them")->required();
  sub->add_option("--t-end", o->t_end, "Time span of each orbit")->required();
  sub->add_option("--dt", o->dt, "Step of the tangent flow (RKMK4; default: the scene's [run] dt)");
  sub->add_option("--seed", o->seed, "Seed of the level-set draws and of the tangent vectors")->capture_default_str();
  sub->add_option("--measure", o->measure,
                  "Density of the draws on each level set: liouville (the phase-space measure) or uniform (Gamma "
                  "uniform on the sphere, lgi's draw before; docs/atlas.md §6)")
      ->capture_default_str();
  sub->add_option("--threshold", o->threshold, "An orbit is chaotic where MEGNO <Y>(t_end) exceeds this")
      ->capture_default_str();
  sub->add_option("--threads", o->threads, "OpenMP threads (default: all cores; at most 64 per core)")->check(thread_count_check());
  sub->add_option("--out", o->out, "Output file (HDF5); required")->required();
  add_force_quiet_flags(*sub, *o, "Replace an existing output file");
  sub->footer(exit_status_help);
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_chaos_map(*o);
          },
          [o] { check_flags(*o); }};
}

}  // namespace lgi::experiments
