#include "experiments/commands/chaos_map/cardan_chaos_map.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>

#include "experiments/analysis/cardan_energy_draw.hpp"
#include "experiments/analysis/cardan_section.hpp"
#include "experiments/analysis/sweep_plan.hpp"
#include "experiments/cli/grid_range.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/commands/chaos_map/cardan_chaos_resume.hpp"
#include "experiments/commands/chaos_map/chaos_map_cells.hpp"
#include "experiments/commands/sweep/sweep_ranks.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "experiments/io/sweep_spec.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "integrators/ensemble/ensemble.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

/// The sweep spec that varies the key over its values: its plan's scene()
/// is the base scene with the key overridden and read again with every rule
/// of the scene reader (experiments/SWEEPS.md, "What varies").
std::string vary_spec_text(const VaryAxis& v, const std::string& scene_path) {
  std::string values;
  for (const double x : v.values) values += (values.empty() ? "" : ", ") + exact_number(x);
  return "name = \"lgi chaos-map --vary\"\nscene = \"" + scene_path + "\"\nscheme = \"cardan-rk4\"\n\n[[vary]]\nkey = \"" +
         v.key + "\"\n" + (v.component ? "component = " + std::to_string(v.component) + "\n" : "") + "values = [" +
         values + "]\n";
}

/// The spec's message without its file, line and table ("--vary: ...").
UsageError vary_error(const std::exception& e) {
  std::string why = e.what();
  if (const auto at = why.find("[vary] key: "); at != std::string::npos) why = why.substr(at + 12);
  else if (const auto v = why.find("[vary] "); v != std::string::npos) why = why.substr(v + 7);
  return UsageError("--vary: " + why);
}

struct Axis {
  std::vector<system::CardanTop> tops;  // one per value of the key
  std::vector<double> u_min;            // the least U of each on a 32³ lattice
};

Axis make_axis(const system::Scene& scene, const VaryAxis& v) {
  const std::string path = std::filesystem::absolute(scene.file).lexically_normal().string();
  Axis a;
  try {
    const SweepSpec spec = parse_sweep_spec(vary_spec_text(v, path), "lgi-chaos-map-vary.toml");
    const SweepPlan plan(spec, scene);
    std::vector<double> flat;
    for (std::size_t j = 0; j < v.values.size(); ++j) {
      plan.inputs(static_cast<std::int64_t>(j), flat);
      a.tops.push_back(cardan_top(plan.scene(flat)));
      a.u_min.push_back(cardan_sampled_minimum_potential(a.tops.back()));
    }
  } catch (const InputError& e) {
    throw vary_error(e);
  }
  return a;
}

/// The first task of each work item of this rank among tasks [begin, end)
/// (task t = cell · ics + index, t ≡ rank mod ranks): runs of up to
/// max_lanes of its tasks with one value of the key (one top), the last
/// entry `end`.
std::vector<std::int64_t> work_items(std::int64_t begin, std::int64_t end, int rank, int ranks, std::int64_t per_top) {
  const std::int64_t first = begin + ((rank - begin % ranks) % ranks + ranks) % ranks;  // the first t ≥ begin of this rank
  std::vector<std::int64_t> starts;
  std::int64_t count = 0, top = -1;
  for (std::int64_t t = first; t < end; t += ranks, ++count) {
    if (count == integrators::ensemble::max_lanes || t / per_top != top) starts.push_back(t), count = 0, top = t / per_top;
  }
  starts.push_back(end);
  return starts;
}

/// This rank's orbits among tasks [begin, end) on `threads` threads, each a
/// function of its cell and index alone; a work item's drawn orbits run
/// together in the SIMD lanes of the T³ tangent flow (the same values bit for
/// bit; docs/ensemble.md, "Cardan tangent flows"). `done` counts the finished
/// orbits for the progress line.
void run_orbits(const CardanChaosMapRequest& r, const Axis& axis, const std::vector<double>& hs,
                std::vector<CardanMapOrbit>& orbits, std::int64_t begin, std::int64_t end, int rank, int ranks,
                SweepProgress& progress, std::int64_t& done) {
  const auto nh = static_cast<std::int64_t>(hs.size());
  const std::vector<std::int64_t> starts = work_items(begin, end, rank, ranks, nh * r.ics);
  const auto items = static_cast<std::int64_t>(starts.size()) - 1;
  const std::optional<integrators::ensemble::Isa> isa = integrators::ensemble::sweep_isa();
#pragma omp parallel num_threads(r.threads)
  {
    std::vector<system::TorusState> x0;
    std::vector<std::int64_t> index;
    std::vector<CardanMapOrbit*> rows, touched;
    std::vector<double> lyapunov, megno;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t item = 0; item < items; ++item) {
      if (interrupt_requested.load(std::memory_order_relaxed)) continue;
      x0.clear(), index.clear(), rows.clear(), touched.clear();
      const std::int64_t j = starts[static_cast<std::size_t>(item)] / (nh * r.ics);
      const system::CardanTop& top = axis.tops[static_cast<std::size_t>(j)];
      std::int64_t count = 0;
      for (std::int64_t t = starts[static_cast<std::size_t>(item)]; t < starts[static_cast<std::size_t>(item + 1)];
           t += ranks) {
        CardanMapOrbit& o = orbits[static_cast<std::size_t>(t)];
        if (o.done) continue;
        ++count;
        const std::int64_t cell = t / r.ics, i = t % r.ics;
        const double h = hs[static_cast<std::size_t>(cell % nh)];
        if (!(h > axis.u_min[static_cast<std::size_t>(j)])) {
          o.done = true;  // an empty cell (status 1): no draw
          continue;
        }
        system::TorusState x;
        if (draw_cardan_energy_point(top, h, r.seed, i, x)) {
          o.drawn = true, o.x0 = x;
          x0.push_back(x), index.push_back(i), rows.push_back(&o);
        }
        o.done = true;  // undone below if a signal cut the run short
        touched.push_back(&o);
      }
      lyapunov.assign(x0.size(), NAN), megno.assign(x0.size(), NAN);
      cardan_orbit_indicators(top, x0, r.t_end, r.dt, r.seed, index, isa, lyapunov, megno, &interrupt_requested);
      const bool cut = interrupt_requested.load(std::memory_order_relaxed);
      for (std::size_t k = 0; k < rows.size(); ++k) rows[k]->lyapunov = lyapunov[k], rows[k]->megno = megno[k];
      for (CardanMapOrbit* o : touched) o->done = !cut;
#pragma omp critical(cardan_chaos_map_progress)
      progress.update(done += cut ? 0 : count, 0);
    }
  }
}

/// /chaos_map and /orbits (experiments/CHAOS_MAP.md, "Cardan tops").
std::vector<TableGroup> result_groups(const CardanChaosMapRequest& r, const VaryAxis& v, const Axis& axis,
                                      const std::vector<double>& hs, const std::vector<CardanMapOrbit>& orbits) {
  const int width = static_cast<int>(hs.size());
  TableColumn vary_col{"vary"}, h_col{"h"}, h_min_col{"h_min"};
  vary_col.real = v.values, h_col.real = hs, h_min_col.real = axis.u_min;
  ChaosCellColumns summary(width);
  std::vector<TableColumn> per = {{"vary"}, {"h"}, {"cell", 1, true}, {"index", 1, true}, {"megno"}, {"lyapunov"},
                                  {"initial_cardan_angles", 3}, {"initial_cardan_momenta", 3}};
  const std::size_t cells = v.values.size() * hs.size();
  for (std::size_t c = 0; c < cells; ++c) {
    const double value = v.values[c / hs.size()], h = hs[c % hs.size()];
    const bool empty = !(h > axis.u_min[c / hs.size()]);
    std::vector<double> megno, lyapunov;
    bool complete = true, any_drawn = false;
    for (std::int64_t i = 0; i < r.ics; ++i) {
      const CardanMapOrbit& o = orbits[c * static_cast<std::size_t>(r.ics) + static_cast<std::size_t>(i)];
      if (!o.done) complete = false;
      if (!o.done || empty) continue;
      any_drawn = any_drawn || o.drawn;
      per[0].real.push_back(value), per[1].real.push_back(h);
      per[2].whole.push_back(static_cast<std::int64_t>(c)), per[3].whole.push_back(i);
      per[4].real.push_back(o.megno), per[5].real.push_back(o.lyapunov);
      per[6].real.insert(per[6].real.end(), o.x0.q.data(), o.x0.q.data() + 3);
      per[7].real.insert(per[7].real.end(), o.x0.p.data(), o.x0.p.data() + 3);
      if (!std::isfinite(o.megno) || !std::isfinite(o.lyapunov)) continue;
      megno.push_back(o.megno), lyapunov.push_back(o.lyapunov);
    }
    const std::int64_t status = empty ? cell_empty : !complete ? cell_not_run : !any_drawn ? cell_unreached : cell_ok;
    summary.add(status, megno, lyapunov, r.threshold);
  }
  TableGroup map{"chaos_map", {vary_col, h_col, h_min_col}};
  for (const TableColumn& c : summary.columns()) map.columns.push_back(c);
  add_chaos_map_attributes(map, r.threshold, "microcanonical",
                           "empty level (h at or below h_min, the least potential on a 32^3 lattice of T^3)",
                           "level not reached by the draw (no state kept in 1e6 tries for any orbit)");
  map.attributes["vary_key"] = v.column();
  return {map, TableGroup{"orbits", per}};
}

/// Where the orbits ran: "avx512 (16 lanes)" or "off" (docs/ensemble.md, "Cardan tangent flows").
std::string simd_note() {
  const std::optional<integrators::ensemble::Isa> isa = integrators::ensemble::sweep_isa();
  if (!isa) return "off";
  return std::string(integrators::ensemble::isa_name(*isa)) + " (" +
         std::to_string(integrators::ensemble::isa_lanes(*isa)) + " lanes)";
}

std::map<std::string, std::string> parameters_of(const system::Scene& scene, const CardanChaosMapRequest& r,
                                                 const VaryAxis& v, double wall, int ranks, bool interrupted) {
  return {{"subcommand", "chaos-map"}, {"system", "cardan (T^3)"}, {"command_line", r.command_line},
          {"scene_file", scene.file}, {"scene_toml", scene.toml_text}, {"lgi_version", build_info::version},
          {"compiler", build_info::compiler}, {"cxx_flags", build_info::cxx_flags}, {"vary", r.vary},
          {"vary_key", v.column()}, {"h_range", r.h_range}, {"ics", std::to_string(r.ics)},
          {"t_end", exact_number(r.t_end)}, {"dt", exact_number(r.dt)}, {"seed", std::to_string(r.seed)},
          {"threshold", exact_number(r.threshold)},
          {"measure", "microcanonical: the Liouville measure of {H = h} on T^3 x R^3 (docs/cardan.md section 9.4)"},
          {"indicators", "RK4 on the state and its tangent (integrators/ensemble/cardan_tangent_kernel.hpp, "
                         "cardan_tangent_ensemble.hpp)"},
          {"simd", simd_note()},
          {"threads", std::to_string(r.threads)}, {"ranks", std::to_string(ranks)},
          {"wall_seconds", format_general(wall, 6)},
          {"status", interrupted ? "interrupted by signal" : "complete"}};
}

}  // namespace

VaryAxis parse_vary_flag(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw UsageError("--vary: \"" + text + "\": expected KEY=a:b:n, e.g. suspension.tilt=0:1.5707963:8");
  VaryAxis v;
  v.key = text.substr(0, eq);
  for (const char ch : v.key)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '.'))
      throw UsageError("--vary: \"" + v.key + "\": a scene key has letters, digits, '_' and '.' only");
  const std::size_t n = v.key.size();
  if (n > 2 && v.key[n - 2] == '_' && v.key[n - 1] >= '1' && v.key[n - 1] <= '3')
    v.component = v.key[n - 1] - '0', v.key.resize(n - 2);
  if (v.key.rfind("initial.", 0) == 0)
    throw UsageError("--vary: \"" + v.key + "\" sets the initial state, which chaos-map draws on each level {H = h}: "
                     "vary a body, gravity or suspension key");
  v.values = parse_grid_range(text.substr(eq + 1), "--vary");
  try {
    (void)parse_sweep_spec(vary_spec_text(v, "/"), "lgi-chaos-map-vary.toml");
  } catch (const InputError& e) {
    VaryAxis one = v;
    one.component = 1;
    try {  // a vector key given whole: name its components
      if (v.component == 0) (void)parse_sweep_spec(vary_spec_text(one, "/"), "lgi-chaos-map-vary.toml");
    } catch (const InputError&) {
      throw vary_error(e);
    }
    if (v.component == 0)
      throw UsageError("--vary: \"" + v.key + "\" has 3 numbers: vary one of them, e.g. " + v.key + "_1=a:b:n");
    throw vary_error(e);
  }
  return v;
}

int run_cardan_chaos_map(const system::Scene& scene, const CardanChaosMapRequest& r) {
  const VaryAxis v = parse_vary_flag(r.vary);
  const std::vector<double> hs = parse_grid_range(r.h_range, "--h-range");
  SweepRanks& ranks = SweepRanks::world();
  const std::string partial = r.out + ".partial";
  const bool from_partial = r.resume && std::filesystem::exists(partial);
  // Rank 0 alone looks at the file system; every rank then refuses alike (no rank left waiting).
  std::string refused;
  try {
    if (ranks.root() && !from_partial) hdf5::check_output_target(r.out, r.force);
  } catch (const OutputFileError& e) {
    refused = e.what();
  }
  std::vector<char> why(refused.begin(), refused.end());
  ranks.broadcast(why);
  if (!why.empty()) throw OutputFileError(std::string(why.begin(), why.end()));
  const Axis axis = make_axis(scene, v);
  std::vector<CardanMapOrbit> orbits(v.values.size() * hs.size() * static_cast<std::size_t>(r.ics));
  const std::string fingerprint = chaos_map_fingerprint(scene, r);
  std::int64_t resumed = 0;
  if (r.resume) resumed = load_partial_orbits(r.out + ".partial", fingerprint, r.ics, orbits, ranks);
  const auto start = std::chrono::steady_clock::now();
  const auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  // Signals only set the flag from before the first file exists until the results are published (interrupt_guard.hpp).
  const InterruptGuard interrupt_guard;
  // Up to 16 rounds, each ended by a gather on rank 0 and a checkpoint in <out>.partial (a killed
  // job loses one round at most); the rounds change no result, every orbit being its own.
  const auto total = static_cast<std::int64_t>(orbits.size());
  const std::int64_t rounds = std::clamp<std::int64_t>(total / (8 * r.threads * ranks.size()), 1, 16);
  bool interrupted = false, checkpointed = false;
  // Progress on stderr from rank 0 (cli/sweep_progress.hpp): in place on a terminal, else a line every
  // 10 s; between the rounds' gathers it counts rank 0's own orbits (all of them on one rank).
  SweepProgress progress(r.quiet || !ranks.root(), total, resumed, "chaos-map", "orbits");
  std::int64_t done = resumed;
  for (std::int64_t k = 0; k < rounds && !interrupted; ++k) {
    run_orbits(r, axis, hs, orbits, total * k / rounds, total * (k + 1) / rounds, ranks.rank(), ranks.size(),
               progress, done);
    gather_orbits(orbits, ranks);
    done = std::count_if(orbits.begin(), orbits.end(), [](const CardanMapOrbit& o) { return o.done; });
    interrupted = ranks.any(interrupt_signal() != 0);
    if (interrupted || k + 1 == rounds || !ranks.root()) continue;
    auto groups = result_groups(r, v, axis, hs, orbits);
    groups.push_back(fingerprint_group(fingerprint));
    auto parameters = parameters_of(scene, r, v, seconds(), ranks.size(), false);
    parameters["status"] = "checkpoint after round " + std::to_string(k + 1) + " of " + std::to_string(rounds);
    write_groups_file(partial, true, groups, parameters);
    checkpointed = true;
  }
  progress.finish();
  const double wall = seconds();
  if (!ranks.root()) return interrupted ? interrupted_exit_status() : exit_ok;
  auto groups = result_groups(r, v, axis, hs, orbits);
  groups.push_back(fingerprint_group(fingerprint));
  const std::string path = interrupted ? partial : r.out;
  write_groups_file(path, r.force || interrupted || from_partial, groups,
                    parameters_of(scene, r, v, wall, ranks.size(), interrupted));
  if (interrupted) {
    std::cerr << "lgi: chaos-map interrupted by signal; the finished orbits are in " << path
              << " (--resume goes on from them)\n";
    return interrupted_exit_status();
  }
  if (from_partial || checkpointed) std::filesystem::remove(partial);
  if (!r.quiet) {
    std::cout << "chaos-map: " << v.values.size() << " x " << hs.size() << " cells of " << v.column() << " and h, "
              << r.ics << " orbits each (microcanonical measure) to t = " << format_general(r.t_end, 6)
              << ", chaotic where MEGNO > " << format_general(r.threshold, 6) << "; " << format_general(wall, 3)
              << " s wall on " << ranks.size() << " x " << r.threads << " threads"
              << (resumed ? " (" + std::to_string(resumed) + " orbits resumed)" : "") << "; wrote " << r.out << '\n';
    print_chaos_fractions(groups[0], "vary", v.column());
  }
  return exit_ok;
}

}  // namespace lgi::experiments
