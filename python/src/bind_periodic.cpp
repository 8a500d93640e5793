// lgi.periodic_orbit() and lgi.continue_family(): the records of `lgi periodic`
// (experiments/PERIODIC.md, analysis/periodic/) as NumPy arrays.
#include <pybind11/complex.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <string>

#include "experiments/analysis/periodic/kovalevskaya_orbits.hpp"
#include "experiments/analysis/periodic/lyapunov_families.hpp"
#include "experiments/commands/atlas/atlas_tables.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

namespace ex = experiments;

ex::HeavyTopBody heavy_top(const system::Scene& scene, const char* what) {
  if (scene.suspension) throw py::value_error(std::string(what) + ": " + scene.file + " is a Cardan top; heavy tops only");
  return ex::equilibria_body(scene);
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
  std::vector<std::int64_t> family(n), index(n), degenerate(n), equilibrium(n), parent(n);
  std::vector<double> l(n), h(n), period(n), pi(3 * n), gamma(3 * n), residual(n), mult(12 * n), omega(n), trivial(n),
      product(n), trace(n), defect(n);
  py::list stability, event, family_end;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& r = rows[i];
    const auto& o = r.orbit;
    family[i] = r.family, index[i] = r.index, degenerate[i] = o.degenerate ? 1 : 0, equilibrium[i] = r.equilibrium;
    parent[i] = r.parent, l[i] = o.l, h[i] = o.h, period[i] = o.period, residual[i] = o.residual, omega[i] = r.omega;
    trivial[i] = o.trivial_deviation, product[i] = o.product_deviation, trace[i] = o.reduced_trace;
    defect[i] = o.invariance_defect;
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

py::dict periodic_orbit(const py::object& scene_arg, const py::object& angular_momentum, const py::object& gamma,
                        double period, std::optional<double> h, std::optional<double> l, double dt) {
  const auto scene = scene_argument(scene_arg);
  const ex::HeavyTopBody body = heavy_top(*scene, "periodic_orbit");
  const ex::Vec6 x = point_of(angular_momentum, gamma);
  if (!(period > 0.0) || !std::isfinite(period)) throw py::value_error("period: must be a positive number");
  if (!(dt > 0.0) || !(dt <= 1.0)) throw py::value_error("dt: must be in (0, 1]");
  if (period / dt > 1e8) throw py::value_error("period, dt: more than 1e8 steps a shot");
  if ((h && !std::isfinite(*h)) || (l && !std::isfinite(*l))) throw py::value_error("h, l: must be finite numbers");
  const auto inv = ex::euler_poisson_invariants(body, x).value;
  ex::ShootingSettings s;
  s.dt = dt;
  ex::FamilyOrbit r;
  {
    const py::gil_scoped_release release;
    r.orbit = ex::correct_orbit(body, x, period, h.value_or(inv(0)), l.value_or(inv(1)), s);
  }
  r.omega = 2.0 * std::acos(-1.0) / r.orbit.period;
  py::dict d = family_columns({r});
  add_appelrot_columns(d, body, {r});
  d["converged"] = r.orbit.converged;
  d["iterations"] = r.orbit.iterations;
  std::vector<double> m(r.orbit.monodromy.data(), r.orbit.monodromy.data() + 36);
  d["monodromy"] = to_numpy(std::move(m), {6, 6}).attr("T");  // Eigen is column-major
  return d;
}

py::dict continue_family(const py::object& scene_arg, double l, const py::object& seed, int steps, double h_step,
                         double dt, double amplitude, std::optional<std::pair<double, double>> h_range, bool events,
                         bool branch_switching) {
  const auto scene = scene_argument(scene_arg);
  const ex::HeavyTopBody body = heavy_top(*scene, "continue_family");
  if (!std::isfinite(l)) throw py::value_error("l: must be a finite number");
  if (steps < 0 || steps > 100000) throw py::value_error("steps: must be in [0, 100000]");
  if (!(h_step > 0.0) || !std::isfinite(h_step)) throw py::value_error("h_step: must be a positive number");
  if (!(dt > 0.0) || !(dt <= 1.0)) throw py::value_error("dt: must be in (0, 1]");
  if (!(amplitude > 0.0) || !(amplitude <= 0.1)) throw py::value_error("amplitude: must be in (0, 0.1]");
  ex::FamilySettings s;
  s.shooting.dt = dt, s.amplitude = amplitude, s.steps = steps, s.h_step = h_step;
  s.locate_events = events, s.switch_branches = branch_switching;
  if (h_range) {
    if (!(h_range->first < h_range->second)) throw py::value_error("h_range: need A < B");
    s.h_min = h_range->first, s.h_max = h_range->second;
  }
  std::vector<ex::FamilyOrbit> rows;
  std::vector<std::string> failures;
  if (seed.is_none()) {
    const py::gil_scoped_release release;
    rows = ex::lyapunov_families(body, l, s, failures);
  } else {
    if (!py::isinstance<py::tuple>(seed) && !py::isinstance<py::list>(seed))
      throw py::value_error("seed: expected (angular_momentum, gamma, period)");
    const auto t = seed.cast<py::tuple>();
    if (t.size() != 3) throw py::value_error("seed: expected (angular_momentum, gamma, period)");
    const ex::Vec6 x = point_of(t[0], t[1]);
    const double T = t[2].cast<double>();
    if (!(T > 0.0) || !std::isfinite(T)) throw py::value_error("seed: the period must be a positive number");
    const py::gil_scoped_release release;
    rows = ex::continue_family(body, x, T, ex::euler_poisson_invariants(body, x).value(0), l, 1.0, 0, s, failures);
  }
  py::dict d = family_columns(rows);
  add_appelrot_columns(d, body, rows);
  d["failures"] = failures;
  return d;
}

}  // namespace

void bind_periodic(py::module_& m) {
  m.def("periodic_orbit", &periodic_orbit, py::arg("scene"), py::arg("angular_momentum"), py::arg("gamma"),
        py::arg("period"), py::arg("h") = py::none(), py::arg("l") = py::none(), py::arg("dt") = 2e-3,
        "One periodic orbit of a heavy top by Newton's method from a point and a period guess, at energy h and "
        "momentum l (default: those of the point), with its Floquet multipliers and stability: the columns of "
        "`lgi periodic`'s /periodic for one row, plus converged, iterations and the 6x6 monodromy "
        "(experiments/PERIODIC.md).");
  m.def("continue_family", &continue_family, py::arg("scene"), py::arg("l"), py::arg("seed") = py::none(),
        py::arg("steps") = 10, py::arg("h_step") = 0.01, py::arg("dt") = 2e-3, py::arg("amplitude") = 1e-4,
        py::arg("h_range") = py::none(), py::arg("events") = true, py::arg("branch_switching") = true,
        "Families of periodic orbits at momentum l, continued by pseudo-arclength with their folds, period "
        "doublings and class changes, and the doubled families: the Lyapunov families of every stable relative "
        "equilibrium (seed=None), or one family from seed=(angular_momentum, gamma, period). The columns of "
        "`lgi periodic`'s /periodic (experiments/PERIODIC.md).");
}

}  // namespace lgi::python
