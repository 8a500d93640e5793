#pragma once
// The tables of the atlas commands, built in memory from the analysis layer:
// `lgi equilibria` / `lgi bifurcation` (experiments/EQUILIBRIA.md) and
// `lgi region` (experiments/REGION.md) write them, and the Python module's
// lgi.equilibria, lgi.bifurcation, lgi.region and lgi.region_cells
// (python/src/bind_atlas.cpp) return them, so both have the same columns
// and the same numbers.
#include <optional>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "experiments/analysis/accessible_region.hpp"
#include "experiments/analysis/kovalevskaya_diagram.hpp"
#include "experiments/analysis/relative_equilibria.hpp"
#include "experiments/io/table_file.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// J and m g χ of a heavy top for `lgi equilibria` / `lgi bifurcation`;
/// InputError naming the scene unless it is a heavy top or a free body.
HeavyTopBody equilibria_body(const system::Scene& scene);

/// The /equilibria columns: omega, gamma, angular_momentum, l, h, branch, g1,
/// g2, stability, nonlinearly_stable, fold, residual, class_change.
std::vector<TableColumn> equilibria_columns(const std::vector<RelativeEquilibrium>& rows);

/// The first 12 of those columns (omega … residual), which the Cardan top's
/// /equilibria table shares (cardan_atlas.cpp), and a row of them from an
/// equilibrium E of either kind.
std::vector<TableColumn> shared_equilibrium_columns();
template <class E>
void push_shared_equilibrium_row(std::vector<TableColumn>& c, const E& e, bool fold) {
  c[0].real.push_back(e.omega);
  c[1].real.insert(c[1].real.end(), e.gamma.data(), e.gamma.data() + 3);
  c[2].real.insert(c[2].real.end(), e.angular_momentum.data(), e.angular_momentum.data() + 3);
  c[3].real.push_back(e.l);
  c[4].real.push_back(e.h);
  c[5].whole.push_back(e.branch);
  c[6].real.push_back(e.g1);
  c[7].real.push_back(e.g2);
  c[8].whole.push_back(static_cast<std::int64_t>(e.stability));
  c[9].whole.push_back(e.nonlinearly_stable ? 1 : 0);
  c[10].whole.push_back(fold ? 1 : 0);
  c[11].real.push_back(e.residual);
}

/// "id: kind" one a line (the /parameters branches attribute).
std::string branch_listing(const std::vector<EquilibriumBranch>& branches);
/// "id: label" per line: each branch named by its asymptotic axes (hanging, upright, +-e_i).
std::string branch_label_listing(const std::vector<EquilibriumBranch>& branches);

/// The energies of --appelrot-h (`range` a:b:n; empty: h/(J3 c) from -1.1 to 5, 123 values).
std::vector<double> appelrot_energies(const KovalevskayaScale& scale, const std::string& range);

/// UsageError naming --h when h is below the least energy at l (an empty level set).
void check_level_not_empty(const HeavyTopBody& body, double l, double h, const std::string& scene_file);

/// `lgi region --l --h`: the grid, the critical points and the region.
struct SingleRegion {
  CriticalSet critical;
  SphereGrid grid;
  Region region;
};
/// `keep_going` (polled per ring of the grid and every 2^20 simplices) false: nullopt.
std::optional<SingleRegion> single_region(const HeavyTopBody& body, double l, double h, int grid,
                                          const std::function<bool()>& keep_going = {});

/// Its groups /potential, /critical_points and /components.
std::vector<TableGroup> single_region_groups(const SingleRegion& r, double h);

/// `lgi region --cells`: the /cells group (with the attribute topology_names)
/// on the raster ls × hs; `unresolved` counts the cells the grid leaves unresolved.
/// `keep_going`, if given, is called with the cells done so far after each cell and, within a
/// row, well under 0.1 s apart (region_summaries); false stops the raster (a signal: the group
/// then holds only the whole rows done).
TableGroup cells_group(const HeavyTopBody& body, const std::vector<double>& ls, const std::vector<double>& hs, int grid,
                       std::int64_t& unresolved, const std::function<bool(std::int64_t)>& keep_going = {});

/// The /equilibria group beside the cells: l, h, omega, branch, stability, fold.
TableGroup branches_group(const HeavyTopBody& body, int samples);

}  // namespace lgi::experiments
