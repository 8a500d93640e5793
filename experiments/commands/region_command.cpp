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
#include <string>

#include "experiments/analysis/accessible_region.hpp"
#include "experiments/analysis/poincare_section.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/grid_range.hpp"
#include "experiments/cli/run_options.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/table_file.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

struct RegionOptions {
  std::string scene, out = "region.h5", l_range, h_range;
  std::optional<double> l, h;
  bool cells = false;
  int grid = 120, samples = 400;
  bool force = false, quiet = false;
  std::string command_line;
};

std::string number(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

const char* index_name(const CriticalPoint& c) {
  static const char* names[] = {"minimum", "saddle", "maximum"};
  return names[std::clamp(c.index, 0, 2)];
}

std::map<std::string, std::string> provenance(const RegionOptions& o, const system::Scene& scene) {
  return {{"subcommand", "region"},         {"command_line", o.command_line},      {"scene_file", scene.file},
          {"scene_toml", scene.toml_text},  {"lgi_version", build_info::version},  {"compiler", build_info::compiler},
          {"cxx_flags", build_info::cxx_flags}, {"grid", std::to_string(o.grid)}};
}

TableGroup potential_group(const SphereGrid& grid, const Region& region) {
  TableGroup g{"potential"};
  TableColumn theta{"theta"}, phi{"phi"}, U{"U", grid.meridians()}, label{"component", grid.meridians(), true};
  for (int i = 0; i <= grid.n; ++i) theta.real.push_back(grid.theta(i));
  for (int j = 0; j < grid.meridians(); ++j) phi.real.push_back(grid.phi(j));
  U.real = grid.U;
  label.whole = region.label;
  g.columns = {theta, phi, U, label};
  return g;
}

TableGroup critical_group(const CriticalSet& set, double h) {
  TableGroup g{"critical_points"};
  std::vector<TableColumn> c = {{"gamma", 3}, {"value"}, {"index", 1, true}, {"circle", 1, true}, {"below", 1, true},
                                {"omega"},    {"branch", 1, true}, {"stability", 1, true}, {"nonlinearly_stable", 1, true},
                                {"degenerate", 1, true}};
  for (const auto& p : set.points) {
    c[0].real.insert(c[0].real.end(), p.gamma.data(), p.gamma.data() + 3);
    c[1].real.push_back(p.value);
    c[2].whole.push_back(p.index);
    c[3].whole.push_back(p.circle ? 1 : 0);
    c[4].whole.push_back(p.value < h ? 1 : 0);
    c[5].real.push_back(p.omega);
    c[6].whole.push_back(p.branch);
    c[7].whole.push_back(static_cast<std::int64_t>(p.stability));
    c[8].whole.push_back(p.nonlinearly_stable ? 1 : 0);
    c[9].whole.push_back(p.degenerate ? 1 : 0);
  }
  g.columns = c;
  return g;
}

TableGroup components_group(const Region& region) {
  TableGroup g{"components"};
  std::vector<TableColumn> c = {{"id", 1, true},     {"boundaries", 1, true}, {"euler", 1, true},
                                {"euler_morse", 1, true}, {"minima", 1, true}, {"saddles", 1, true},
                                {"maxima", 1, true}, {"circles", 1, true},    {"area"}, {"u_min"}};
  std::string names;
  for (const auto& k : region.components) {
    c[0].whole.push_back(k.id), c[1].whole.push_back(k.boundaries), c[2].whole.push_back(k.euler);
    c[3].whole.push_back(k.euler_morse), c[4].whole.push_back(k.minima), c[5].whole.push_back(k.saddles);
    c[6].whole.push_back(k.maxima), c[7].whole.push_back(k.circles);
    c[8].real.push_back(k.area), c[9].real.push_back(k.u_min);
    names += (names.empty() ? "" : "\n") + k.topology;
  }
  g.columns = c;
  g.attributes["topology"] = names;
  return g;
}

/// The checks that need no file (run at parse time and again before a run).
void check_flags(const RegionOptions& o) {
  if (o.grid < 8 || o.grid > 2000) throw UsageError("--grid: must be between 8 and 2000");
  if (o.samples < 3) throw UsageError("--samples: must be at least 3");
  if (o.cells) {
    if (o.l || o.h) throw UsageError(std::string(o.l ? "--l" : "--h") + ": not with --cells (give --l-range and --h-range)");
    if (o.l_range.empty() || o.h_range.empty())
      throw UsageError(std::string(o.l_range.empty() ? "--l-range" : "--h-range") + ": required with --cells");
    parse_grid_range(o.l_range, "--l-range");
    parse_grid_range(o.h_range, "--h-range");
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
  const double lowest = minimum_energy(body, l);
  if (h < lowest - 1e-12 * std::max(1.0, std::abs(lowest)))
    throw UsageError("--h: h is below the minimum energy at this l: h = " + number(h) + " < " + number(lowest) +
                     " = min H at l = " + number(l) + " for " + scene.file + " (the level set is empty)");
  const CriticalSet critical = critical_points(body, l);
  const SphereGrid grid = potential_grid(body, l, o.grid);
  const Region region = accessible_region(grid, critical, h);
  auto parameters = provenance(o, scene);
  parameters["l"] = number(l), parameters["h"] = number(h), parameters["topology"] = region.topology;
  parameters["resolved"] = region.resolved ? "yes" : "no";
  parameters["degenerate"] = region.degenerate ? "yes" : "no";
  parameters["u_constant"] = critical.constant ? "yes" : "no";
  write_groups_file(o.out, o.force,
                    {potential_group(grid, region), critical_group(critical, h), components_group(region)}, parameters);
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

/// The index of `name` in `names`, appended if new.
std::int64_t code_of(std::vector<std::string>& names, const std::string& name) {
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == name) return static_cast<std::int64_t>(k);
  names.push_back(name);
  return static_cast<std::int64_t>(names.size() - 1);
}

TableGroup branches_group(const HeavyTopBody& body, int samples) {
  TableGroup g{"equilibria"};
  std::vector<TableColumn> c = {{"l"}, {"h"}, {"omega"}, {"branch", 1, true}, {"stability", 1, true}, {"fold", 1, true}};
  for (const auto& e : equilibrium_branches(body, samples).rows) {
    if (e.class_change) continue;  // a point between two samples: the curves are drawn from the samples
    c[0].real.push_back(e.l), c[1].real.push_back(e.h), c[2].real.push_back(e.omega);
    c[3].whole.push_back(e.branch), c[4].whole.push_back(static_cast<std::int64_t>(e.stability));
    c[5].whole.push_back(e.fold ? 1 : 0);
  }
  g.columns = c;
  return g;
}

int run_cells(const RegionOptions& o, const system::Scene& scene, const HeavyTopBody& body) {
  const std::vector<double> ls = parse_grid_range(o.l_range, "--l-range"), hs = parse_grid_range(o.h_range, "--h-range");
  std::vector<std::string> names = {"empty"};
  TableColumn l_col{"l"}, h_col{"h"}, h_min{"h_min"};
  const int width = static_cast<int>(hs.size());
  TableColumn topology{"topology", width, true}, components{"components", width, true}, euler{"euler", width, true},
      euler_morse{"euler_morse", width, true}, resolved{"resolved", width, true},
      degenerate{"degenerate", width, true};
  h_col.real = hs;
  std::int64_t unresolved = 0;
  for (const double l : ls) {
    l_col.real.push_back(l);
    h_min.real.push_back(minimum_energy(body, l));
    const auto summaries = region_summaries(potential_grid(body, l, o.grid), critical_points(body, l), hs);
    for (const auto& s : summaries) {
      topology.whole.push_back(code_of(names, s.topology));
      components.whole.push_back(s.components);
      euler.whole.push_back(s.euler), euler_morse.whole.push_back(s.euler_morse);
      resolved.whole.push_back(s.resolved ? 1 : 0);
      degenerate.whole.push_back(s.degenerate ? 1 : 0);
      unresolved += s.resolved ? 0 : 1;
    }
  }
  TableGroup cells{"cells", {l_col, h_col, h_min, topology, components, euler, euler_morse, resolved, degenerate}};
  std::string legend;
  for (const auto& n : names) legend += (legend.empty() ? "" : "\n") + n;
  cells.attributes["topology_names"] = legend;
  auto parameters = provenance(o, scene);
  parameters["l_range"] = o.l_range, parameters["h_range"] = o.h_range;
  write_groups_file(o.out, o.force, {cells, branches_group(body, o.samples)}, parameters);
  if (o.quiet) return exit_ok;
  std::map<std::int64_t, std::int64_t> count;
  for (const auto code : topology.whole) ++count[code];
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
  sub->add_option("--out", o->out, "Output file (HDF5)")->capture_default_str();
  add_force_quiet_flags(*sub, *o, "Replace an existing output file");
  return {sub,
          [o, context] {
            o->command_line = context.command_line;
            return run_region(*o);
          },
          [o] { check_flags(*o); }};
}

}  // namespace lgi::experiments
