// The atlas of heavy tops (docs/atlas.md) from Python: lgi.equilibria,
// lgi.bifurcation, lgi.region, lgi.region_cells and lgi.poincare. The first
// four build the tables of `lgi equilibria`, `lgi bifurcation` and
// `lgi region` in memory with the commands' own code
// (experiments/commands/atlas/atlas_tables.hpp); lgi.poincare runs
// `lgi poincare` in-process (run_poincare_request: the same checks, sweep
// engine and file) and reads its file back. Every table is a dict of NumPy
// arrays under the column names of the command's HDF5 file
// (experiments/EQUILIBRIA.md, REGION.md, POINCARE.md).
#include <pybind11/stl.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "experiments/commands/poincare_request.hpp"
#include "experiments/cli/grid_range.hpp"
#include "experiments/cli/thread_count.hpp"
#include "experiments/commands/atlas/atlas_tables.hpp"
#include "experiments/errors/exit_status.hpp"
#include "python/src/bindings.hpp"
#include "python/src/hdf5_columns.hpp"

namespace lgi::python {
namespace {

namespace ex = experiments;
namespace fs = std::filesystem;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// A column as (rows,) or (rows, width), int64 or float64 (the vector moves into NumPy).
py::array table_column_array(ex::TableColumn c) {
  const auto w = static_cast<py::ssize_t>(c.width);
  if (c.integer) {
    const auto rows = static_cast<py::ssize_t>(c.whole.size()) / w;
    return w == 1 ? py::array(to_numpy(std::move(c.whole), {rows})) : py::array(to_numpy(std::move(c.whole), {rows, w}));
  }
  const auto rows = static_cast<py::ssize_t>(c.real.size()) / w;
  return w == 1 ? py::array(to_numpy(std::move(c.real), {rows})) : py::array(to_numpy(std::move(c.real), {rows, w}));
}

void add_columns(py::dict& d, std::vector<ex::TableColumn> columns) {
  for (auto& c : columns) {
    const std::string name = c.name;
    d[py::str(name)] = table_column_array(std::move(c));
  }
}

/// A group's columns, and its attributes: the lists of names (topology,
/// topology_names) as lists of str, the others as str.
py::dict table_group_dict(ex::TableGroup g) {
  py::dict d;
  add_columns(d, std::move(g.columns));
  for (const auto& [key, value] : g.attributes) {
    if (d.contains(py::str(key)))  // an attribute must not hide a column of the same name
      throw std::logic_error("table group " + g.name + ": attribute " + key + " has the name of a column");
    d[py::str(key)] = key == "topology" || key == "topology_names" ? py::object(py::cast(lines_of(value)))
                                                                   : py::object(py::str(value));
  }
  return d;
}

std::shared_ptr<const system::Scene> heavy_top_scene(const py::object& scene_arg, const std::string& function) {
  auto scene = scene_argument(scene_arg);
  if (scene->suspension)
    throw py::value_error(scene->file + ": [suspension]: lgi." + function +
                          " takes a top on SO(3); for a Cardan top run the command lgi " + function +
                          " (docs/cardan.md)");
  return scene;
}

py::dict equilibria_dict(const ex::EquilibriumSet& set) {
  py::dict d;
  add_columns(d, ex::equilibria_columns(set.rows));
  py::dict branches;
  for (const auto& b : set.branches) branches[py::int_(b.id)] = b.kind;
  d["branches"] = branches;
  return d;
}

py::dict equilibria(const py::object& scene_arg, double l) {
  if (!std::isfinite(l)) throw py::value_error("--l: must be a finite number");
  const auto scene = heavy_top_scene(scene_arg, "equilibria");
  const ex::HeavyTopBody body = ex::equilibria_body(*scene);
  ex::EquilibriumSet set;
  {
    const py::gil_scoped_release release;
    set = ex::equilibria_at(body, l);
  }
  return equilibria_dict(set);
}

py::dict bifurcation(const py::object& scene_arg, int samples, const std::optional<std::vector<double>>& appelrot,
                     const std::optional<std::string>& appelrot_h) {
  if (samples < 3) throw py::value_error("--samples: must be at least 3");
  const auto scene = heavy_top_scene(scene_arg, "bifurcation");
  const ex::HeavyTopBody body = ex::equilibria_body(*scene);
  std::optional<ex::KovalevskayaScale> scale;
  std::vector<double> hs;
  if (appelrot) {
    for (const double l : *appelrot)
      if (!std::isfinite(l)) throw py::value_error("--appelrot: the values of l must be finite numbers");
    scale = ex::kovalevskaya_scale(body);
    if (!scale)
      throw py::value_error("--appelrot: " + scene->file +
                            " is not a Kovalevskaya top (J = J3 diag(2, 2, 1), centre of mass on e1)");
    hs = ex::appelrot_energies(*scale, appelrot_h.value_or(""));
  } else if (appelrot_h) {
    throw py::value_error("--appelrot-h: only with --appelrot");
  }
  ex::EquilibriumSet set;
  std::vector<ex::TableGroup> groups;
  {
    const py::gil_scoped_release release;
    set = ex::equilibrium_branches(body, samples);
    if (appelrot) groups = ex::appelrot_groups(body, *scale, *appelrot, hs);
  }
  py::dict d = equilibria_dict(set);
  for (auto& g : groups) {
    const std::string name = g.name;
    d[py::str(name)] = table_group_dict(std::move(g));
  }
  return d;
}

void check_grid(int grid) {
  if (grid < 8 || grid > 2000) throw py::value_error("--grid: must be between 8 and 2000");
}

py::dict region(const py::object& scene_arg, double l, double h, int grid) {
  if (!std::isfinite(l)) throw py::value_error("--l: must be a finite number");
  if (!std::isfinite(h)) throw py::value_error("--h: must be a finite number");
  check_grid(grid);
  const auto scene = heavy_top_scene(scene_arg, "region");
  const ex::HeavyTopBody body = ex::heavy_top_of(*scene, "region");
  ex::check_level_not_empty(body, l, h, scene->file);
  std::optional<ex::SingleRegion> single;
  {
    const py::gil_scoped_release release;
    single = ex::single_region(body, l, h, grid);
  }
  py::dict d;
  for (auto& g : ex::single_region_groups(*single, h)) {
    const std::string name = g.name;
    d[py::str(name)] = table_group_dict(std::move(g));
  }
  d["l"] = l;
  d["h"] = h;
  d["grid"] = grid;
  d["topology"] = single->region.topology;
  d["resolved"] = single->region.resolved;
  d["u_constant"] = single->critical.constant;
  return d;
}

/// A raster a:b:n given as text or as (a, b, n), read by the command's parser.
std::vector<double> grid_range(const py::object& range, const std::string& flag) {
  if (py::isinstance<py::str>(range)) return ex::parse_grid_range(range.cast<std::string>(), flag);
  const auto t = range.cast<std::tuple<double, double, long long>>();
  char text[96];
  std::snprintf(text, sizeof text, "%.17g:%.17g:%lld", std::get<0>(t), std::get<1>(t), std::get<2>(t));
  return ex::parse_grid_range(text, flag);
}

py::dict region_cells(const py::object& scene_arg, const py::object& l_range, const py::object& h_range, int grid,
                      int samples) {
  check_grid(grid);
  if (samples < 3) throw py::value_error("--samples: must be at least 3");
  const std::vector<double> ls = grid_range(l_range, "--l-range"), hs = grid_range(h_range, "--h-range");
  const auto scene = heavy_top_scene(scene_arg, "region");
  const ex::HeavyTopBody body = ex::heavy_top_of(*scene, "region");
  std::int64_t unresolved = 0;
  std::optional<ex::TableGroup> cells, branches;
  {
    const py::gil_scoped_release release;
    cells = ex::cells_group(body, ls, hs, grid, unresolved);
    branches = ex::branches_group(body, samples);
  }
  py::dict d;
  d["cells"] = table_group_dict(std::move(*cells));
  d["equilibria"] = table_group_dict(std::move(*branches));
  d["unresolved"] = unresolved;
  return d;
}

/// The scene file lgi poincare reads: a path as given; an lgi.Scene's own file
/// when it still holds the scene's text, else the text written into `folder`.
std::string poincare_scene_file(const py::object& scene_arg, const TemporaryFolder& folder) {
  if (!py::isinstance<PyScene>(scene_arg)) {
    scene_argument(scene_arg);  // TypeError / ValueError as for every scene argument
    return py::str(scene_arg).cast<std::string>();
  }
  const system::Scene& scene = *scene_arg.cast<const PyScene&>().scene;
  std::error_code ec;
  if (fs::is_regular_file(scene.file, ec)) {
    std::ifstream in(scene.file);
    std::ostringstream text;
    text << in.rdbuf();
    if (text.str() == scene.toml_text) return scene.file;
  }
  const std::string path = (fs::path(folder.path) / "scene.toml").string();
  std::ofstream(path) << scene.toml_text;
  return path;
}

std::string poincare_call(const ex::PoincareRequest& r) {
  std::ostringstream s;
  s.precision(17);
  s << "lgi.poincare(scene='" << r.scene << "', l=" << r.l << ", h=" << r.h << ", ics=" << r.ics
    << ", t_end=" << r.t_end;
  if (r.dt) s << ", dt=" << *r.dt;
  s << ", seed=" << r.seed << ", lyapunov=" << (r.lyapunov ? "True" : "False")
    << ", megno=" << (r.megno ? "True" : "False") << ")";
  return s.str();
}

struct PoincareArguments {
  double l, h;
  std::int64_t ics;
  double t_end;
  std::optional<double> dt;
  bool megno, lyapunov;
  std::uint64_t seed;
  std::optional<std::string> axis, section, scheme;
  std::int64_t max_events;
  int threads;
  std::optional<std::string> out;
  bool force;
};

py::dict poincare(const py::object& scene_arg, const PoincareArguments& a) {
  if (a.threads < 1 || a.threads > ex::max_threads())
    throw py::value_error("threads: must be from 1 to " + std::to_string(ex::max_threads()) + " (64 per core)");
  const TemporaryFolder folder("lgi-poincare");
  ex::PoincareRequest r;
  r.scene = poincare_scene_file(scene_arg, folder);
  r.out = a.out ? *a.out : (fs::path(folder.path) / "poincare.h5").string();
  r.l = a.l, r.h = a.h, r.ics = a.ics, r.t_end = a.t_end, r.dt = a.dt, r.seed = a.seed;
  r.megno = a.megno, r.lyapunov = a.lyapunov, r.max_events = a.max_events, r.threads = a.threads;
  r.axis = a.axis.value_or(""), r.section = a.section.value_or("richter"), r.scheme = a.scheme.value_or("");
  r.force = a.force, r.quiet = true;
  r.command_line = poincare_call(r);
  int status = 0;
  {
    const py::gil_scoped_release release;
    status = ex::run_poincare_request(r);
  }
  if (status == ex::exit_interrupted_sigint) {  // Ctrl-C stopped the orbits (interrupt_guard.hpp)
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  if (status != 0)
    throw std::runtime_error("lgi.poincare: the section did not complete (exit status " + std::to_string(status) + ")");
  py::dict d;
  d["sweep"] = group_dict(r.out, "/sweep");
  d["events"] = group_dict(r.out, "/events");
  d["parameters"] = attributes_dict(r.out, "/parameters");
  d["out"] = a.out ? py::object(py::str(*a.out)) : py::none();
  return d;
}

}  // namespace

void bind_atlas(py::module_& m) {
  m.def("equilibria", &equilibria, py::arg("scene"), py::arg("l"),
        "equilibria(scene, l) -> dict: every relative equilibrium at l (`lgi equilibria --l`), sorted by h:\n"
        "the /equilibria columns omega, gamma (n, 3), angular_momentum (n, 3), l, h, branch, g1, g2,\n"
        "stability (0 stable, 1 singly, 2 doubly, 3 complex unstable), nonlinearly_stable, fold, residual,\n"
        "and branches {id: kind}. ValueError for a scene that is not a heavy top (lgi's message).");
  m.def("bifurcation", &bifurcation, py::arg("scene"), py::arg("samples") = 400, py::arg("appelrot") = py::none(),
        py::arg("appelrot_h") = py::none(),
        "bifurcation(scene, samples=400, appelrot=None, appelrot_h=None) -> dict: every branch of relative\n"
        "equilibria sampled with its folds (`lgi bifurcation`): the columns of lgi.equilibria, and branches.\n"
        "appelrot=[l, ...] on a Kovalevskaya top adds the dicts appelrot, appelrot_equilibria and\n"
        "appelrot_range (--appelrot; appelrot_h 'a:b:n' is --appelrot-h).");
  m.def("region", &region, py::arg("scene"), py::arg("l"), py::arg("h"), py::arg("grid") = 120,
        "region(scene, l, h, grid=120) -> dict: `lgi region --l --h`: the dicts potential (theta, phi,\n"
        "U (n+1, 2n), component), critical_points (gamma, value, index, circle, below, omega, branch,\n"
        "stability, nonlinearly_stable) and components (id, boundaries, euler, euler_morse, minima,\n"
        "saddles, maxima, circles, area, u_min, topology: one name per component), and topology (the\n"
        "energy surface: 'S3', '2S3', 'S1xS2', 'RP3', ...), resolved, u_constant, l, h, grid.\n"
        "ValueError ('--h: h is below the minimum energy at this l: ...') for an empty level.");
  m.def("region_cells", &region_cells, py::arg("scene"), py::arg("l_range"), py::arg("h_range"),
        py::arg("grid") = 120, py::arg("samples") = 400,
        "region_cells(scene, l_range, h_range, grid=120, samples=400) -> dict: `lgi region --cells`: the\n"
        "topology of the energy surface on the raster l_range x h_range (each (a, b, n) or 'a:b:n'):\n"
        "cells (l, h, h_min, and (n_l, n_h) arrays topology (an index into topology_names), components,\n"
        "euler, euler_morse, resolved), equilibria (l, h, omega, branch, stability, fold) and unresolved.");
  m.def(
      "poincare",
      [](const py::object& scene, double l, double h, std::int64_t ics, double t_end, std::optional<double> dt,
         bool megno, bool lyapunov, std::uint64_t seed, std::optional<std::string> axis,
         std::optional<std::string> section, std::optional<std::string> scheme, std::int64_t max_events, int threads,
         std::optional<std::string> out, bool force) {
        return poincare(scene, {l, h, ics, t_end, dt, megno, lyapunov, seed, std::move(axis), std::move(section),
                                std::move(scheme), max_events, threads, std::move(out), force});
      },
      py::arg("scene"), py::arg("l"), py::arg("h"), py::arg("ics"), py::arg("t_end"), py::arg("dt") = py::none(),
      py::arg("megno") = false, py::arg("lyapunov") = false, py::arg("seed") = 0, py::arg("axis") = py::none(),
      py::arg("section") = py::none(), py::arg("scheme") = py::none(), py::arg("max_events") = 100000,
      py::arg("threads") = 1, py::arg("out") = py::none(), py::arg("force") = false,
      "poincare(scene, l, h, ics, t_end, dt=None, megno=False, lyapunov=False, seed=0, axis=None,\n"
      "section=None, scheme=None, max_events=100000, threads=1, out=None, force=False) -> dict:\n"
      "`lgi poincare` in-process (the flags of the same names). Returns the dicts events (one row per\n"
      "crossing: index, event, direction, step, t, angular_momentum, orientation, gamma, phi, theta,\n"
      "sheet) and sweep (one row per orbit, with lyapunov and megno when asked), parameters (the\n"
      "file's /parameters attributes) and out. With out= the file is kept there, as the CLI writes it;\n"
      "otherwise nothing is left on disk. The numbers are the command's, bit for bit, for any threads.\n"
      "ValueError for bad flags or an empty level (lgi's message); the GIL is released.");
}

}  // namespace lgi::python
