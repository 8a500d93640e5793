// The tables of lgi equilibria, lgi bifurcation and lgi region, shared with
// the Python module (atlas_tables.hpp; layouts: experiments/EQUILIBRIA.md,
// experiments/REGION.md).
#include "experiments/commands/atlas/atlas_tables.hpp"

#include <optional>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "experiments/analysis/poincare_section.hpp"
#include "experiments/cli/grid_range.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/number_format.hpp"

namespace lgi::experiments {
namespace {


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

/// The index of `name` in `names`, appended if new.
std::int64_t code_of(std::vector<std::string>& names, const std::string& name) {
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == name) return static_cast<std::int64_t>(k);
  names.push_back(name);
  return static_cast<std::int64_t>(names.size() - 1);
}

}  // namespace

HeavyTopBody equilibria_body(const system::Scene& scene) {
  const bool gravity = scene.declared<system::GravityTerm>().has_value();
  if (!scene.is_free_body() && !scene.declares_only<system::GravityTerm>())
    throw InputError(scene.file + ": lgi equilibria needs a heavy top (gravity and no other torque term)");
  HeavyTopBody body;
  body.J = scene.inertia;
  if (gravity)
    body.weight = *scene.mass * scene.declared<system::GravityTerm>()->g * scene.center_of_mass.value_or(Vec3::Zero());
  return body;
}

std::vector<TableColumn> shared_equilibrium_columns() {
  return {{"omega"}, {"gamma", 3}, {"angular_momentum", 3}, {"l"},  {"h"},
          {"branch", 1, true}, {"g1"}, {"g2"}, {"stability", 1, true}, {"nonlinearly_stable", 1, true},
          {"fold", 1, true}, {"residual"}};
}

std::vector<TableColumn> equilibria_columns(const std::vector<RelativeEquilibrium>& rows) {
  std::vector<TableColumn> c = shared_equilibrium_columns();
  c.push_back({"class_change", 1, true});
  for (const auto& e : rows) {
    push_shared_equilibrium_row(c, e, e.fold);
    c[12].whole.push_back(e.class_change ? 1 : 0);
  }
  return c;
}

std::string branch_listing(const std::vector<EquilibriumBranch>& branches) {
  std::string text;
  for (const auto& b : branches) text += std::to_string(b.id) + ": " + b.kind + "\n";
  return text;
}

std::string branch_label_listing(const std::vector<EquilibriumBranch>& branches) {
  std::string text;
  for (const auto& b : branches) text += std::to_string(b.id) + ": " + b.label + "\n";
  return text;
}

std::vector<double> appelrot_energies(const KovalevskayaScale& scale, const std::string& range) {
  const double unit = scale.J3 * scale.c;
  const std::string text =
      range.empty() ? format_general(-1.1 * unit, 17) + ":" + format_general(5.0 * unit, 17) + ":123" : range;
  return parse_grid_range(text, "--appelrot-h");
}

void check_level_not_empty(const HeavyTopBody& body, double l, double h, const std::string& scene_file) {
  const double lowest = minimum_energy(body, l);
  if (h < lowest - 1e-12 * std::max(1.0, std::abs(lowest)))
    throw UsageError("--h: h is below the minimum energy at this l: h = " + format_exact(h) + " < " + format_exact(lowest) +
                     " = min H at l = " + format_exact(l) + " for " + scene_file + " (the level set is empty)");
}

std::optional<SingleRegion> single_region(const HeavyTopBody& body, double l, double h, int grid,
                                          const std::function<bool()>& keep_going) {
  SingleRegion r;
  r.critical = critical_points(body, l);
  r.grid = potential_grid(body, l, grid, keep_going);
  if (keep_going && !keep_going()) return std::nullopt;  // also when the grid was cut short
  std::optional<Region> region = keep_going ? accessible_region(r.grid, r.critical, h, keep_going)
                                            : std::optional<Region>(accessible_region(r.grid, r.critical, h));
  if (!region) return std::nullopt;
  r.region = std::move(*region);
  return r;
}

std::vector<TableGroup> single_region_groups(const SingleRegion& r, double h) {
  return {potential_group(r.grid, r.region), critical_group(r.critical, h), components_group(r.region)};
}

TableGroup cells_group(const HeavyTopBody& body, const std::vector<double>& ls, const std::vector<double>& hs, int grid,
                       std::int64_t& unresolved, const std::function<bool(std::int64_t)>& keep_going) {
  std::vector<std::string> names = {"empty"};
  TableColumn l_col{"l"}, h_col{"h"}, h_min{"h_min"};
  const int width = static_cast<int>(hs.size());
  TableColumn topology{"topology", width, true}, components{"components", width, true}, euler{"euler", width, true},
      euler_morse{"euler_morse", width, true}, resolved{"resolved", width, true},
      degenerate{"degenerate", width, true};
  h_col.real = hs;
  unresolved = 0;
  std::function<bool(std::size_t)> cell_done;  // within a row: the cells before it and those of it done
  if (keep_going)
    cell_done = [&](std::size_t k) {
      return keep_going(static_cast<std::int64_t>(topology.whole.size() + k));
    };
  for (const double l : ls) {
    if (keep_going && !keep_going(static_cast<std::int64_t>(topology.whole.size()))) break;
    const double least = minimum_energy(body, l);
    const auto row_start = [&] { return cell_done(0); };
    SphereGrid potential = potential_grid(body, l, grid, keep_going ? std::function<bool()>(row_start) : nullptr);
    if (potential.n == 0) break;  // stopped
    const auto summaries = region_summaries(potential, critical_points(body, l), hs, cell_done);
    if (summaries.size() != hs.size()) break;  // stopped within the row: it is not kept
    l_col.real.push_back(l);
    h_min.real.push_back(least);
    for (const auto& s : summaries) {
      topology.whole.push_back(code_of(names, s.topology));
      components.whole.push_back(s.components);
      euler.whole.push_back(s.euler), euler_morse.whole.push_back(s.euler_morse);
      resolved.whole.push_back(s.resolved ? 1 : 0);
      degenerate.whole.push_back(s.degenerate ? 1 : 0);
      unresolved += s.resolved ? 0 : 1;
    }
  }
  if (keep_going && l_col.real.size() == ls.size()) keep_going(static_cast<std::int64_t>(topology.whole.size()));
  TableGroup cells{"cells", {l_col, h_col, h_min, topology, components, euler, euler_morse, resolved, degenerate}};
  std::string legend;
  for (const auto& n : names) legend += (legend.empty() ? "" : "\n") + n;
  cells.attributes["topology_names"] = legend;
  return cells;
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

}  // namespace lgi::experiments
