// lgi region --scene FILE --l L --h H [--grid N] [--out FILE.h5] [--force] [--quiet]
// lgi region --scene FILE --cells --l-range a:b:n --h-range a:b:n [--grid N] [--samples N] [--out FILE.h5]
// The amended potential of a heavy top on the Poisson sphere, its critical
// points, the accessible region {U_l <= h} with its components and the
// topology of the energy surface; with --cells, that topology on a raster of
// the (l, h) bifurcation diagram (analysis/accessible_region.hpp; layout and
// meaning: experiments/REGION.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "experiments/analysis/accessible_region.hpp"
#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/sweep_progress.hpp"
#include "experiments/cli/work_limits.hpp"
#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/grid_range.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/commands/atlas/atlas_tables.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/hdf5_support.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/table_file.hpp"
#include "experiments/io/trajectory_observer.hpp"  // interrupt_requested
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

struct RegionOptions {
  std::string scene, out, l_range, h_range;
  std::optional<double> l, h;
  bool cells = false;
  int grid = 120, samples = 400;
  bool force = false, quiet = false;
  std::string command_line;
};


const char* index_name(const CriticalPoint& c) {
  static const char* names[] = {"minimum", "saddle", "maximum"};
  return names[std::clamp(c.index, 0, 2)];
}

std::map<std::string, std::string> provenance(const RegionOptions& o, const system::Scene& scene) {
  return {{"subcommand", "region"},         {"command_line", o.command_line},      {"scene_file", scene.file},
          {"scene_toml", scene.toml_text},  {"lgi_version", build_info::version},  {"compiler", build_info::compiler},
          {"cxx_flags", build_info::cxx_flags}, {"grid", std::to_string(o.grid)}};
}

/// The checks that need no file (run at parse time and again before a run).
void check_flags(const RegionOptions& o) {
  if (o.grid < 8 || o.grid > 2000) throw UsageError("--grid: must be between 8 and 2000");
  if (o.samples < 3) throw UsageError("--samples: must be at least 3");
  check_work_limit("--samples", o.samples, max_branch_samples, "points per branch");
  if (o.cells) {
    if (o.l || o.h) throw UsageError(std::string(o.l ? "--l" : "--h") + ": not with --cells (give --l-range and --h-range)");
    if (o.l_range.empty() || o.h_range.empty())
      throw UsageError(std::string(o.l_range.empty() ? "--l-range" : "--h-range") + ": required with --cells");
    const auto cells = static_cast<std::int64_t>(parse_grid_range(o.l_range, "--l-range").size() *
                                                 parse_grid_range(o.h_range, "--h-range").size());
    check_work_limit("--cells", cells, max_grid_cells, "cells (--l-range x --h-range)");
    return;
  }
  if (!o.l || !o.h) throw UsageError(std::string(o.l ? "--h" : "--l") + ": required (or --cells with --l-range and --h-range)");
  if (!std::isfinite(*o.l)) throw UsageError("--l: must be a finite number");
  if (!std::isfinite(*o.h)) throw UsageError("--h: must be a finite number");
  if (!o.l_range.empty() || !o.h_range.empty())
    throw UsageError(std::string(o.l_range.empty() ? "--h-range" : "--l-range") + ": only with --cells");
}

int run_single(const RegionOptions& o, const system::Scene& scene, const HeavyTopBody& body) {
  const double l = *o.l, h = *o.h;
  check_level_not_empty(body, l, h, scene.file);
  const InterruptGuard interrupt_guard;  // kept until the file is written
  const std::optional<SingleRegion> computed =
      single_region(body, l, h, o.grid, [] { return !interrupt_requested.load(); });
  if (!computed) {
    std::cerr << "lgi: region: interrupted by signal before the region was complete; nothing written\n";
    return interrupted_exit_status();
  }
  const SingleRegion& single = *computed;
  const CriticalSet& critical = single.critical;
  const Region& region = single.region;
  auto parameters = provenance(o, scene);
  parameters["l"] = format_exact(l), parameters["h"] = format_exact(h), parameters["topology"] = region.topology;
  parameters["resolved"] = region.resolved ? "yes" : "no";
  parameters["degenerate"] = region.degenerate ? "yes" : "no";
  parameters["u_constant"] = critical.constant ? "yes" : "no";
  write_groups_file(o.out, o.force, single_region_groups(single, h), parameters);
  if (o.quiet) return exit_ok;
  for (const auto& c : critical.points)
    std::printf("critical point: gamma=(%.6g, %.6g, %.6g) U=%.6g %s%s omega=%.6g branch=%d\n", c.gamma.x(),
                c.gamma.y(), c.gamma.z(), c.value, index_name(c), c.circle ? " (on a circle of critical points)" : "",
                c.omega, c.branch);
  for (const auto& k : region.components)
    std::printf("component %d: %s (%d boundary circle%s, chi = %d; Morse: %d minima, %d saddles, %d maxima, %d on "
                "circles), %.4g of the sphere\n",
                k.id, k.topology.c_str(), k.boundaries, k.boundaries == 1 ? "" : "s", k.euler, k.minima, k.saddles,
                k.maxima, k.circles, k.area);
  std::cout << "region: l = " << format_general(l, 6) << ", h = " << format_general(h, 6) << ": energy surface " << region.topology
            << (region.resolved ? "" : " (not resolved by the grid: raise --grid)")
            << (region.degenerate ? " (U_l has a degenerate critical point below h, a bifurcation of relative "
                                    "equilibria at this l: the topology is the grid's, without the Morse check)"
                                  : "")
            << "; wrote " << o.out << '\n';
  return exit_ok;
}

int run_cells(const RegionOptions& o, const system::Scene& scene, const HeavyTopBody& body) {
  const std::vector<double> ls = parse_grid_range(o.l_range, "--l-range"), hs = parse_grid_range(o.h_range, "--h-range");
  std::int64_t unresolved = 0;
  hdf5::check_output_target(o.out, o.force);  // before the work, not after it
  // Progress on stderr (cli/sweep_progress.hpp; issue 50, item 8). A signal is read after every cell and
  // within a row's triangulation, sort and sweep (well under a second apart, atlas_tables.hpp); the
  // raster stops there and nothing is written (the file is written only at the end).
  const auto total = static_cast<std::int64_t>(ls.size() * hs.size());
  SweepProgress progress(o.quiet, total, 0, "region --cells", "cells");
  const InterruptGuard interrupt_guard;
  std::int64_t done = 0;
  const TableGroup cells = cells_group(body, ls, hs, o.grid, unresolved, [&](std::int64_t cells_done) {
    if (interrupt_requested.load()) return false;
    if (cells_done != done) progress.update(done = cells_done, 0);
    return true;
  });
  progress.finish();
  if (cells.columns[0].real.size() != ls.size()) {  // cut short by a signal
    std::cerr << "lgi: region --cells: interrupted by signal after " << done << " of " << total
              << " cells; nothing written\n";
    return interrupted_exit_status();
  }
  auto parameters = provenance(o, scene);
  parameters["l_range"] = o.l_range, parameters["h_range"] = o.h_range;
  write_groups_file(o.out, o.force, {cells, branches_group(body, o.samples)}, parameters);
  if (o.quiet) return exit_ok;
  std::vector<std::string> names;
  std::istringstream legend(cells.attributes.at("topology_names"));
  for (std::string line; std::getline(legend, line);) names.push_back(line);
  std::map<std::int64_t, std::int64_t> count;
  for (const auto code : cells.columns[3].whole) ++count[code];  // topology
  for (const auto& [code, n] : count) std::cout << "topology " << names[static_cast<std::size_t>(code)] << ": " << n << " cells\n";
  std::cout << "region --cells: " << ls.size() << " x " << hs.size() << " cells, " << unresolved
            << " not resolved by the grid; wrote " << o.out << '\n';
  return exit_ok;
}

int run_region(const RegionOptions& o) {
  check_flags(o);
  const system::Scene scene = read_scene(o.scene);
  refuse_cardan_scene(scene, "region");
  const HeavyTopBody body = heavy_top_of(scene, "region");
  return o.cells ? run_cells(o, scene, body) : run_single(o, scene, body);
}

}  // namespace

Subcommand add_region_subcommand(CLI::App& app, const CommandContext& context) {
  auto o = std::make_shared<RegionOptions>();
  auto* sub = app.add_subcommand(
      "region",
      "The amended potential of a heavy top on the Poisson sphere, its critical points, the accessible region "
      "U_l <= h and the topology of the energy surface; --cells: that topology over the (l, h) plane "
      "(experiments/REGION.md)");
  sub->add_option("--scene", o->scene, "Scene file (TOML): a heavy top, or a free body")->required();
  sub->add_option("--l", o->l, "l = Pi.Gamma, the vertical angular momentum");
  sub->add_option("--h", o->h, "h, the energy");
  sub->add_flag("--cells", o->cells, "Label a raster of the (l, h) plane with the energy surface's topology");
  sub->add_option("--l-range", o->l_range, "With --cells: l values a:b:n (n from a to b)");
  sub->add_option("--h-range", o->h_range, "With --cells: h values a:b:n");
  sub->add_option("--grid", o->grid, "Sphere grid: theta in n + 1 rings, phi in 2n meridians")->capture_default_str();
  sub->add_option("--samples", o->samples, "With --cells: points per branch of the equilibria written beside")
      ->capture_default_str();
  sub->add_option("--out", o->out, "Output file (HDF5); required")->required();
  add_force_quiet_flags(*sub, *o, "Replace an existing output file");
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_region(*o);
          },
          [o] { check_flags(*o); }};
}

}  // namespace lgi::experiments
