// lgi.periodic_orbit() and lgi.continue_family(): the records of `lgi periodic`
// (experiments/PERIODIC.md, analysis/periodic/) as NumPy arrays.
#include <pybind11/complex.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "experiments/analysis/periodic/kovalevskaya_orbits.hpp"
#include "experiments/analysis/periodic/lyapunov_families.hpp"
#include "experiments/commands/atlas/atlas_tables.hpp"
#include "experiments/commands/periodic/periodic_run.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

namespace ex = experiments;

/// A scene's flow for lgi periodic: a heavy top, or a Cardan top with a cyclic outer
/// angle (the CLI's refusal of a tilted frame, naming suspension.tilt, as ValueError).
struct SceneFlow {
  std::optional<system::CardanTop> top;
  std::optional<ex::PeriodicFlow> flow;
};

void flow_of(SceneFlow& f, const system::Scene& scene, const char* what) {
  if (!scene.suspension) {
    f.flow.emplace(ex::equilibria_body(scene));
    return;
  }
  f.top.emplace(ex::cardan_top(scene));
  if (const std::string why = ex::cardan_tilt_refusal(*f.top, scene.file); !why.empty())
    throw py::value_error(std::string(what) + ": " + why);
  f.flow.emplace(*f.top);
}

/// A Cardan top's point (q, p) as the CLI's seed line: q1 dropped (0, it is cyclic).
ex::Vec6 cardan_point_of(const py::object& q_arg, const py::object& p_arg) {
  const auto q = q_arg.cast<std::vector<double>>(), p = p_arg.cast<std::vector<double>>();
  if (q.size() != 3 || p.size() != 3) throw py::value_error("a Cardan scene's point: expected q and p as 3-vectors");
  ex::Vec6 x;
  x << 0.0, q[1], q[2], p[0], p[1], p[2];
  if (!x.allFinite()) throw py::value_error("a Cardan scene's point: q and p must be finite");
  return x;
}

/// Every column of `lgi periodic`'s /periodic for `rows`, as the CLI writes them (periodic_columns).
py::dict table_columns(std::vector<ex::TableColumn> columns) {
  py::dict d;
  for (ex::TableColumn& c : columns) {
    const std::string name = c.name;
    if (c.is_text) {
      d[py::str(name)] = py::cast(c.text);
      continue;
    }
    const auto w = static_cast<py::ssize_t>(c.width);
    const auto rows = static_cast<py::ssize_t>(c.integer ? c.whole.size() : c.real.size()) / w;
    std::vector<py::ssize_t> shape{rows};
    if (w > 1) shape.push_back(w);
    d[py::str(name)] = c.integer ? py::array(to_numpy(std::move(c.whole), shape)) : py::array(to_numpy(std::move(c.real), shape));
  }
  return d;
}

ex::Vec6 point_of(const py::object& angular_momentum, const py::object& gamma) {
  const auto pi = angular_momentum.cast<std::vector<double>>(), g = gamma.cast<std::vector<double>>();
  if (pi.size() != 3 || g.size() != 3) throw py::value_error("angular_momentum and gamma: expected 3-vectors");
  ex::Vec6 x;
  x << pi[0], pi[1], pi[2], g[0], g[1], g[2];
  if (!x.allFinite() || x.tail<3>().norm() == 0.0) throw py::value_error("angular_momentum, gamma: finite, gamma nonzero");
  return x;
}

/// The columns of /periodic for `rows` (experiments/PERIODIC.md).
py::dict family_columns(const std::vector<ex::FamilyOrbit>& rows) {
  const std::size_t n = rows.size();
  std::vector<std::int64_t> family(n), index(n), degenerate(n), equilibrium(n), parent(n), pieces(n);
  std::vector<double> l(n), h(n), period(n), pi(3 * n), gamma(3 * n), residual(n), mult(12 * n), omega(n), trivial(n),
      product(n), trace(n), defect(n);
  py::list stability, event, family_end;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& r = rows[i];
    const auto& o = r.orbit;
    family[i] = r.family, index[i] = r.index, degenerate[i] = o.degenerate ? 1 : 0, equilibrium[i] = r.equilibrium;
    parent[i] = r.parent, l[i] = o.l, h[i] = o.h, period[i] = o.period, residual[i] = o.residual, omega[i] = r.omega;
    trivial[i] = o.trivial_deviation, product[i] = o.product_deviation, trace[i] = o.reduced_trace;
    defect[i] = o.invariance_defect, pieces[i] = static_cast<std::int64_t>(o.pieces.size());
    for (std::size_t k = 0; k < 3; ++k) pi[3 * i + k] = o.x0(static_cast<int>(k)), gamma[3 * i + k] = o.x0(static_cast<int>(k) + 3);
    for (std::size_t k = 0; k < 6; ++k) mult[12 * i + 2 * k] = o.multipliers[k].real(), mult[12 * i + 2 * k + 1] = o.multipliers[k].imag();
    stability.append(o.stability), event.append(r.event), family_end.append(r.family_end);
  }
  const auto N = static_cast<py::ssize_t>(n);
  py::dict d;
  d["family"] = to_numpy(std::move(family), {N}), d["index"] = to_numpy(std::move(index), {N});
  d["l"] = to_numpy(std::move(l), {N}), d["h"] = to_numpy(std::move(h), {N});
  d["period"] = to_numpy(std::move(period), {N});
  d["angular_momentum"] = to_numpy(std::move(pi), {N, 3}), d["gamma"] = to_numpy(std::move(gamma), {N, 3});
  d["residual"] = to_numpy(std::move(residual), {N}), d["multipliers"] = to_numpy(std::move(mult), {N, 6, 2});
  d["stability"] = stability, d["event"] = event, d["family_end"] = family_end;
  d["degenerate"] = to_numpy(std::move(degenerate), {N}), d["equilibrium"] = to_numpy(std::move(equilibrium), {N});
  d["omega"] = to_numpy(std::move(omega), {N}), d["trivial_deviation"] = to_numpy(std::move(trivial), {N});
  d["product_deviation"] = to_numpy(std::move(product), {N}), d["parent"] = to_numpy(std::move(parent), {N});
  d["reduced_trace"] = to_numpy(std::move(trace), {N}), d["invariance_defect"] = to_numpy(std::move(defect), {N});
  d["monodromy_pieces"] = to_numpy(std::move(pieces), {N});
  return d;
}

/// The Kovalevskaya columns of /periodic (k, appelrot_family, appelrot_distance,
/// critical_rank_gap; NaN and -1 on other tops), added to d.
void add_appelrot_columns(py::dict& d, const ex::HeavyTopBody& body, const std::vector<ex::FamilyOrbit>& rows) {
  const std::size_t n = rows.size();
  std::vector<double> k(n), distance(n), gap(n);
  std::vector<std::int64_t> family(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto a = ex::appelrot_check(body, rows[i].orbit.x0, rows[i].orbit.l, rows[i].orbit.h);
    k[i] = a.k, family[i] = a.family, distance[i] = a.distance, gap[i] = a.rank_gap;
  }
  const auto N = static_cast<py::ssize_t>(n);
  d["k"] = to_numpy(std::move(k), {N}), d["appelrot_family"] = to_numpy(std::move(family), {N});
  d["appelrot_distance"] = to_numpy(std::move(distance), {N}), d["critical_rank_gap"] = to_numpy(std::move(gap), {N});
}

/// The columns of `rows`: a heavy top's (with the Kovalevskaya ones), or on a Cardan top
/// those of periodic_columns, the CLI's (angular_momentum, gamma the body's; cardan_*).
py::dict rows_columns(const SceneFlow& f, const std::vector<ex::FamilyOrbit>& rows,
                      const std::optional<ex::PhaseSection>& section = std::nullopt) {
  if (f.top) return table_columns(ex::periodic_columns(*f.flow, rows, section));
  py::dict d = family_columns(rows);
  add_appelrot_columns(d, f.flow->body, rows);
  return d;
}

py::dict periodic_orbit(const py::object& scene_arg, const py::object& angular_momentum, const py::object& gamma,
                        double period, std::optional<double> h, std::optional<double> l, double dt,
                        int shooting_points) {
  const auto scene = scene_argument(scene_arg);
  SceneFlow f;
  flow_of(f, *scene, "periodic_orbit");
  const ex::Vec6 x = f.top ? cardan_point_of(angular_momentum, gamma) : point_of(angular_momentum, gamma);
  if (!(period > 0.0) || !std::isfinite(period)) throw py::value_error("period: must be a positive number");
  if (!(dt > 0.0) || !(dt <= 1.0)) throw py::value_error("dt: must be in (0, 1]");
  if (period / dt > 1e8) throw py::value_error("period, dt: more than 1e8 steps a shot");
  if ((h && !std::isfinite(*h)) || (l && !std::isfinite(*l))) throw py::value_error("h, l: must be finite numbers");
  if (shooting_points < 1 || shooting_points > 1000) throw py::value_error("shooting_points: must be in [1, 1000]");
  const auto inv = ex::flow_invariants(*f.flow, x).value;
  // As the CLI's Cardan seeds (q1 q2 q3 p1 p2 p3 T): p1 is the momentum ℓ, not a guess of it.
  if (f.top && l && std::abs(x(3) - *l) > 1e-9 * std::max(1.0, std::abs(*l)))
    throw py::value_error("periodic_orbit: a Cardan scene's p1 is l: p1 = " + std::to_string(x(3)) + ", l = " + std::to_string(*l));
  ex::ShootingSettings s;
  s.dt = dt, s.shooting_points = shooting_points;
  ex::FamilyOrbit r;
  {
    const py::gil_scoped_release release;
    r.orbit = ex::correct_orbit(*f.flow, x, period, h.value_or(inv(0)), l.value_or(inv(1)), s);
  }
  r.omega = 2.0 * std::acos(-1.0) / r.orbit.period;
  py::dict d = rows_columns(f, {r});
  d["converged"] = r.orbit.converged;
  d["iterations"] = r.orbit.iterations;
  std::vector<double> m(r.orbit.monodromy.data(), r.orbit.monodromy.data() + 36);
  d["monodromy"] = to_numpy(std::move(m), {6, 6}).attr("T");  // Eigen is column-major
  return d;
}

/// /manifolds as a dict of columns (text columns as lists of str).
py::dict manifold_columns(const SceneFlow& f, const std::vector<ex::RowManifolds>& manifolds) {
  return table_columns(ex::manifold_group(*f.flow, manifolds).columns);
}

/// The starts of continue_family: a seed (angular_momentum, gamma, period), or a poincare file's rows and points.
void starts_of(ex::PeriodicRequest& r, bool cardan, const py::object& seed, const py::object& poincare,
               const py::object& poincare_rows, const py::object& poincare_points) {
  if (!seed.is_none() && !poincare.is_none()) throw py::value_error("seed, seeds_from_poincare: give at most one");
  if (poincare.is_none()) {
    if (!poincare_rows.is_none() || !poincare_points.is_none())
      throw py::value_error("poincare_rows, poincare_points: only with seeds_from_poincare");
    r.from_equilibria = seed.is_none();
    if (seed.is_none()) return;
    if (!py::isinstance<py::tuple>(seed) && !py::isinstance<py::list>(seed))
      throw py::value_error("seed: expected (angular_momentum, gamma, period)");
    const auto t = seed.cast<py::tuple>();
    if (t.size() != 3) throw py::value_error("seed: expected (angular_momentum, gamma, period)");
    const ex::Vec6 x = cardan ? cardan_point_of(t[0], t[1]) : point_of(t[0], t[1]);
    const double T = t[2].cast<double>();
    if (!(T > 0.0) || !std::isfinite(T)) throw py::value_error("seed: the period must be a positive number");
    r.seeds.push_back({x, T});
    return;
  }
  r.poincare = py::str(poincare).cast<std::string>();
  if (!poincare_rows.is_none())
    for (const auto row : poincare_rows.cast<std::vector<std::int64_t>>())
      r.poincare_rows += (r.poincare_rows.empty() ? "" : ",") + std::to_string(row);
  if (!poincare_points.is_none())
    for (const auto& pt : poincare_points.cast<std::vector<std::vector<double>>>()) {
      if (pt.size() != 3) throw py::value_error("poincare_points: expected (phi, theta, sheet) triples");
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g", pt[0], pt[1], pt[2]);
      r.poincare_points.emplace_back(buf);
    }
  if (r.poincare_rows.empty() && r.poincare_points.empty())
    throw py::value_error("seeds_from_poincare: give poincare_rows or poincare_points");
}

struct FamilyOptions {
  int steps = 10, shooting_points = 1, returns = 1, manifolds = 0;
  double direction = 1.0;
  double h_step = 0.01, l_step = 0.01, dt = 2e-3, amplitude = 1e-4, manifold_periods = 4.0, manifold_epsilon = 1e-5;
  std::string continue_in = "h";
  std::optional<std::pair<double, double>> h_range, l_range;
  bool events = true, branch_switching = true;
};

/// The settings of `lgi periodic` from continue_family's keywords (ValueError naming the keyword).
ex::FamilySettings settings_of(const FamilyOptions& o) {
  if (o.steps < 0 || o.steps > 100000) throw py::value_error("steps: must be in [0, 100000]");
  if (!(o.h_step > 0.0) || !std::isfinite(o.h_step)) throw py::value_error("h_step: must be a positive number");
  if (!(o.l_step != 0.0) || !std::isfinite(o.l_step)) throw py::value_error("l_step: must be a nonzero number");
  if (!(o.dt > 0.0) || !(o.dt <= 1.0)) throw py::value_error("dt: must be in (0, 1]");
  if (!(o.amplitude > 0.0) || !(o.amplitude <= 0.1)) throw py::value_error("amplitude: must be in (0, 0.1]");
  if (o.shooting_points < 1 || o.shooting_points > 1000) throw py::value_error("shooting_points: must be in [1, 1000]");
  if (o.continue_in != "h" && o.continue_in != "l") throw py::value_error("continue_in: expected 'h' or 'l'");
  if (o.returns < 1 || o.returns > 1000) throw py::value_error("returns: must be in [1, 1000]");
  if (o.manifolds < 0 || o.manifolds > 100000) throw py::value_error("manifolds: must be in [0, 100000]");
  if (!(o.manifold_periods > 0.0) || !(o.manifold_periods <= 1000.0)) throw py::value_error("manifold_periods: must be in (0, 1000]");
  if (!(o.manifold_epsilon > 0.0) || !(o.manifold_epsilon <= 0.1)) throw py::value_error("manifold_epsilon: must be in (0, 0.1]");
  const bool in_l = o.continue_in == "l";
  ex::FamilySettings s;
  s.shooting.dt = o.dt, s.shooting.in_l = in_l, s.shooting.shooting_points = o.shooting_points;
  s.amplitude = o.amplitude, s.steps = o.steps;
  s.h_step = in_l ? std::abs(o.l_step) : o.h_step, s.start_h_step = o.h_step;
  s.locate_events = o.events, s.switch_branches = o.branch_switching;
  const auto& range = in_l ? o.l_range : o.h_range;
  if (range) {
    if (!(range->first < range->second)) throw py::value_error(in_l ? "l_range: need A < B" : "h_range: need A < B");
    s.h_min = range->first, s.h_max = range->second;
  }
  return s;
}

py::dict continue_family(const py::object& scene_arg, const py::object& l, const py::object& seed, const FamilyOptions& o,
                         const py::object& poincare, const py::object& poincare_rows, const py::object& poincare_points) {
  const auto scene = scene_argument(scene_arg);
  SceneFlow f;
  flow_of(f, *scene, "continue_family");
  ex::PeriodicRequest r;
  if (!l.is_none()) r.l = l.cast<double>();
  if ((r.l && !std::isfinite(*r.l)) || (!r.l && poincare.is_none())) throw py::value_error("l: must be a finite number");
  r.settings = settings_of(o);
  if (o.direction != 1.0 && o.direction != -1.0) throw py::value_error("direction: expected 1 or -1");
  r.direction = o.continue_in == "l" ? (o.l_step < 0.0 ? -1.0 : 1.0) : o.direction;
  r.returns = o.returns;
  r.manifolds.points = o.manifolds, r.manifolds.periods = o.manifold_periods;
  r.manifolds.epsilon = o.manifold_epsilon, r.manifolds.dt = o.dt;
  if (o.manifolds > 0 && poincare.is_none()) throw py::value_error("manifolds: only with seeds_from_poincare");
  starts_of(r, f.top.has_value(), seed, poincare, poincare_rows, poincare_points);
  ex::PeriodicResult result;
  {
    const py::gil_scoped_release release;
    result = ex::periodic_families(*f.flow, r);
  }
  py::dict d = rows_columns(f, result.rows, result.section);
  d["failures"] = result.failures;
  d["l_file"] = result.l;
  if (o.manifolds > 0) d["manifolds"] = manifold_columns(f, result.manifolds);
  return d;
}

}  // namespace

void bind_periodic(py::module_& m) {
  m.def("periodic_orbit", &periodic_orbit, py::arg("scene"), py::arg("angular_momentum"), py::arg("gamma"),
        py::arg("period"), py::arg("h") = py::none(), py::arg("l") = py::none(), py::arg("dt") = 2e-3,
        py::arg("shooting_points") = 1,
        "One periodic orbit of a heavy top by Newton's method from a point and a period guess, at energy h and "
        "momentum l (default: those of the point), by single (shooting_points=1) or multiple shooting, with its "
        "Floquet multipliers and stability: the columns of `lgi periodic`'s /periodic for one row, plus converged, "
        "iterations and the 6x6 monodromy. On a Cardan scene with a vertical outer axis the point is (q, p) in the "
        "places of (angular_momentum, gamma), reduced at p1 = l, with the CLI's Cardan columns "
        "(experiments/PERIODIC.md).");
  m.def(
      "continue_family",
      [](const py::object& scene, const py::object& l, const py::object& seed, int steps, double h_step, double dt,
         double amplitude, std::optional<std::pair<double, double>> h_range, bool events, bool branch_switching,
         const std::string& continue_in, double l_step, std::optional<std::pair<double, double>> l_range,
         int shooting_points, const py::object& seeds_from_poincare, const py::object& poincare_rows,
         const py::object& poincare_points, int returns, int manifolds, double manifold_periods,
         double manifold_epsilon, double direction) {
        FamilyOptions o;
        o.steps = steps, o.h_step = h_step, o.dt = dt, o.amplitude = amplitude, o.h_range = h_range;
        o.events = events, o.branch_switching = branch_switching, o.continue_in = continue_in, o.l_step = l_step;
        o.l_range = l_range, o.shooting_points = shooting_points, o.returns = returns, o.manifolds = manifolds;
        o.manifold_periods = manifold_periods, o.manifold_epsilon = manifold_epsilon, o.direction = direction;
        return continue_family(scene, l, seed, o, seeds_from_poincare, poincare_rows, poincare_points);
      },
      py::arg("scene"), py::arg("l") = py::none(), py::arg("seed") = py::none(), py::arg("steps") = 10,
      py::arg("h_step") = 0.01, py::arg("dt") = 2e-3, py::arg("amplitude") = 1e-4, py::arg("h_range") = py::none(),
      py::arg("events") = true, py::arg("branch_switching") = true, py::arg("continue_in") = "h",
      py::arg("l_step") = 0.01, py::arg("l_range") = py::none(), py::arg("shooting_points") = 1,
      py::arg("seeds_from_poincare") = py::none(), py::arg("poincare_rows") = py::none(),
      py::arg("poincare_points") = py::none(), py::arg("returns") = 1, py::arg("manifolds") = 0,
      py::arg("manifold_periods") = 4.0, py::arg("manifold_epsilon") = 1e-5, py::arg("direction") = 1.0,
      "Families of periodic orbits, continued by pseudo-arclength in h at fixed l (continue_in='h') or in l at "
      "fixed h ('l', first step l_step; a seed's first step in h goes the sense of direction=+-1), with their folds, period doublings and class changes, and the doubled "
      "families (branch_switching): the Lyapunov families of every stable relative equilibrium (no seed), one "
      "family from seed=(angular_momentum, gamma, period), or one per seed of a `lgi poincare` file "
      "(seeds_from_poincare=path with poincare_rows=[...] and/or poincare_points=[(phi, theta, sheet), ...]; l "
      "may be left out), with manifolds=N the stable and unstable manifolds of its hyperbolic orbits "
      "(d['manifolds']); shooting_points=M > 1 corrects by multiple shooting. The columns of `lgi periodic`'s "
      "/periodic, failures and l_file (the l used). On a Cardan scene with a vertical outer axis: its equilibria's "
      "families, seed=(q, p, period), or the seeds of a Cardan poincare file (poincare_points (x, y, piece)), the "
      "CLI's Cardan columns (experiments/PERIODIC.md).");
}

}  // namespace lgi::python
