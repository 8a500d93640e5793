// lgi.indicators(): the records of `lgi indicators` for chosen states
// (experiments/INDICATORS.md, analysis/chaos_indicators.hpp); lgi.tangent_flow():
// the state and tangent vectors advanced together (integrators/core/tangent_flow.hpp);
// and the state dicts both take (also Stepper.state's setter).
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <variant>

#include "experiments/analysis/chaos_indicators.hpp"
#include "integrators/ensemble/tangent_ensemble.hpp"
#include "experiments/io/gamma_attitude.hpp"
#include "experiments/io/state_file.hpp"
#include "integrators/system/model.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// Rows of n×3 (or one 3-vector) from `obj`, named `what` in errors.
std::vector<lie::Vec3> vectors(const py::handle& obj, const std::string& what) {
  const Array a = Array::ensure(obj);
  if (!a || a.size() % 3 != 0 || a.ndim() > 2 || a.shape(a.ndim() - 1) != 3)
    throw py::value_error(what + ": expected a 3-vector or an (n, 3) array");
  std::vector<lie::Vec3> out;
  for (py::ssize_t i = 0; i < a.size(); i += 3) out.emplace_back(a.data()[i], a.data()[i + 1], a.data()[i + 2]);
  return out;
}

experiments::StateRows state_rows(const py::object& states) {
  if (py::isinstance<py::str>(states) || py::hasattr(states, "__fspath__"))
    return experiments::read_state_file(py::module_::import("os").attr("fspath")(states).cast<std::string>());
  if (!py::isinstance<py::dict>(states))
    throw py::value_error("states: expected None, a state file's path, or a dict with angular_momentum and gamma");
  const py::dict d = states.cast<py::dict>();
  if (!d.contains("angular_momentum") || !d.contains("gamma"))
    throw py::value_error("states: the dict needs angular_momentum and gamma ((n, 3) arrays)");
  experiments::StateRows r{vectors(d["angular_momentum"], "states['angular_momentum']"),
                           vectors(d["gamma"], "states['gamma']"), "dict"};
  if (r.angular_momentum.size() != r.gamma.size())
    throw py::value_error("states: angular_momentum and gamma have different numbers of rows");
  if (r.gamma.empty()) throw py::value_error("states: no rows");
  return r;
}

/// The GALI outputs: log10_gali_2..6 at T per state, and "gali", the /gali group of the file.
void add_gali(py::dict& d, const std::vector<experiments::StateIndicators>& r) {
  std::vector<std::int64_t> index;
  std::vector<double> t, curves;
  std::vector<std::vector<double>> last(experiments::gali_orders);
  for (std::size_t i = 0; i < r.size(); ++i) {
    for (std::size_t j = 0; j < r[i].gali.t.size(); ++j) {
      index.push_back(static_cast<std::int64_t>(i)), t.push_back(r[i].gali.t[j]);
      curves.insert(curves.end(), r[i].gali.log10_gali[j].begin(), r[i].gali.log10_gali[j].end());
    }
    for (std::size_t k = 0; k < last.size(); ++k) last[k].push_back(r[i].gali.log10_gali.back()[k]);
  }
  const auto rows = static_cast<py::ssize_t>(r.size()), samples = static_cast<py::ssize_t>(t.size());
  for (std::size_t k = 0; k < last.size(); ++k)
    d[py::str("log10_gali_" + std::to_string(k + 2))] = to_numpy(std::move(last[k]), {rows});
  py::dict g;
  g["index"] = to_numpy(std::move(index), {samples});
  g["t"] = to_numpy(std::move(t), {samples});
  g["log10_gali"] = to_numpy(std::move(curves), {samples, experiments::gali_orders});
  d["gali"] = g;
}

py::dict indicators(const py::object& scene_arg, std::optional<double> t_end, std::optional<double> dt,
                    const py::object& states, bool spectrum, std::uint64_t seed, double rtol, bool gali,
                    int gali_samples, const std::string& gali_spacing) {
  const std::shared_ptr<const system::Scene> scene = scene_argument(scene_arg);
  const bool cardan = scene->suspension.has_value();
  if (cardan && !states.is_none())
    throw py::value_error("states: " + scene->file + " is a Cardan top; its [initial] state only (states=None)");
  if (gali_samples < 1 || gali_samples > 100000) throw py::value_error("gali_samples: must be in 1..100000");
  if (gali_spacing != "log" && gali_spacing != "linear") throw py::value_error("gali_spacing: 'log' or 'linear'");
  experiments::IndicatorSettings s;
  s.t_end = t_end ? *t_end : scene->t_end.value_or(0.0);
  s.dt = dt ? *dt : scene->dt.value_or(0.0);
  if (!(s.t_end > 0.0) || !std::isfinite(s.t_end)) throw py::value_error("t_end: missing or not a positive number");
  if (!(s.dt > 0.0) || !std::isfinite(s.dt)) throw py::value_error("dt: missing or not a positive number");
  if (!(rtol > 0.0)) throw py::value_error("rtol: must be > 0");
  s.seed = seed, s.spectrum = spectrum, s.rtol = rtol, s.gali = gali;
  s.gali_sampling = {gali_samples, gali_spacing == "log"};
  std::vector<system::State> x0 = {scene->initial};
  if (!states.is_none()) {
    int normalised = 0;
    x0 = experiments::states_of(state_rows(states), "states", normalised);
  }
  const std::size_t n = x0.size();
  std::vector<experiments::StateIndicators> r(n);
  {
    const py::gil_scoped_release release;
    for (std::size_t i = 0; i < n; ++i)
      r[i] = cardan ? experiments::cardan_state_indicators(*scene, scene->cardan_initial, s, static_cast<std::int64_t>(i))
                    : experiments::state_indicators(*scene, x0[i], s, static_cast<std::int64_t>(i));
  }
  std::vector<std::int64_t> index(n), converged(n);
  std::vector<double> lyapunov(n), half(n), megno(n), te(n), pi(3 * n), gamma(3 * n), spec(6 * n);
  for (std::size_t i = 0; i < n; ++i) {
    index[i] = static_cast<std::int64_t>(i), converged[i] = r[i].converged ? 1 : 0;
    lyapunov[i] = r[i].lyapunov, half[i] = r[i].lyapunov_last_half, megno[i] = r[i].megno, te[i] = r[i].t_end;
    const lie::Vec3 g = x0[i].R.transpose() * lie::Vec3::UnitZ();
    for (std::size_t k = 0; k < 3; ++k) pi[3 * i + k] = x0[i].Pi[static_cast<int>(k)], gamma[3 * i + k] = g[static_cast<int>(k)];
    for (std::size_t k = 0; k < 6; ++k) spec[6 * i + k] = r[i].spectrum[k];
  }
  const auto rows = static_cast<py::ssize_t>(n);
  py::dict d;
  d["index"] = to_numpy(std::move(index), {rows});
  d["lyapunov"] = to_numpy(std::move(lyapunov), {rows});
  d["lyapunov_last_half"] = to_numpy(std::move(half), {rows});
  d["megno"] = to_numpy(std::move(megno), {rows});
  d["t_end"] = to_numpy(std::move(te), {rows});
  d["converged"] = to_numpy(std::move(converged), {rows});
  d["angular_momentum"] = to_numpy(std::move(pi), {rows, 3});
  d["gamma"] = to_numpy(std::move(gamma), {rows, 3});
  if (spectrum) d["spectrum"] = to_numpy(std::move(spec), {rows, 6});
  if (gali) add_gali(d, r);
  if (cardan) {
    const system::TorusState& c = scene->cardan_initial;
    d["cardan_angles"] = to_numpy(std::vector<double>(c.q.data(), c.q.data() + 3), {1, 3});
    d["cardan_momenta"] = to_numpy(std::vector<double>(c.p.data(), c.p.data() + 3), {1, 3});
  }
  return d;
}

py::dict tangent_flow(const py::object& scene_arg, const py::dict& state, const py::object& v_arg, double dt,
                      std::int64_t steps, double t0) {
  const std::shared_ptr<const system::Scene> scene = scene_argument(scene_arg);
  if (scene->suspension) throw py::value_error("tangent_flow: " + scene->file + " is a Cardan top; SO(3) scenes only");
  if (!(dt > 0.0) || !std::isfinite(dt)) throw py::value_error("dt: must be a finite number > 0");
  if (steps < 0) throw py::value_error("steps: must be >= 0");
  system::State x = state_from_dict(state);
  const Array v = Array::ensure(v_arg);
  if (!v || v.ndim() < 1 || v.ndim() > 2 || v.shape(0) != 6 || (v.ndim() == 2 && v.shape(1) > 6))
    throw py::value_error("v: expected a 6-vector (xi, dPi) or a (6, k) array of k <= 6 tangent vectors as columns");
  const py::ssize_t k = v.ndim() == 2 ? v.shape(1) : 1;
  integrators::Mat6 V = integrators::Mat6::Zero();  // zero columns stay zero: the flow is linear in V
  for (py::ssize_t r = 0; r < 6; ++r)
    for (py::ssize_t c = 0; c < k; ++c) V(r, c) = v.data()[r * k + c];
  {
    const py::gil_scoped_release release;
    const system::AnyModel model = system::make_model(*scene);
    // The indicators' step (integrators/ensemble/tangent_ensemble.hpp): that of the SIMD lanes where the model has them.
    integrators::ensemble::with_tangent_step(model, [&](auto step) {
      for (std::int64_t i = 0; i < steps; ++i) step(x, V, t0 + static_cast<double>(i) * dt, dt);
      return 0;
    });
  }
  std::vector<double> out(static_cast<std::size_t>(6 * k));
  for (py::ssize_t r = 0; r < 6; ++r)
    for (py::ssize_t c = 0; c < k; ++c) out[static_cast<std::size_t>(r * k + c)] = V(r, c);
  py::dict d = state_dict(x);
  d["v"] = v.ndim() == 2 ? to_numpy(std::move(out), {6, k}) : to_numpy(std::move(out), {6});
  d["t"] = t0 + static_cast<double>(steps) * dt;
  return d;
}

}  // namespace

py::dict state_dict(const system::State& x) {
  std::vector<double> R(9);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R[static_cast<std::size_t>(3 * r + c)] = x.R(r, c);
  py::dict d;
  d["R"] = to_numpy(std::move(R), {3, 3});
  d["Pi"] = to_numpy(std::vector<double>{x.Pi[0], x.Pi[1], x.Pi[2]}, {3});
  return d;
}

system::State state_from_dict(const py::dict& d) {
  if (!d.contains("Pi") || (d.contains("R") == d.contains("gamma")))
    throw py::value_error("state: expected a dict with Pi (3,) and either R (3, 3) or gamma (3,)");
  const std::vector<lie::Vec3> pi = vectors(d["Pi"], "state['Pi']");
  if (pi.size() != 1 || !pi[0].allFinite()) throw py::value_error("state['Pi']: expected 3 finite numbers");
  system::State x;
  x.Pi = pi[0];
  if (d.contains("gamma")) {
    const std::vector<lie::Vec3> g = vectors(d["gamma"], "state['gamma']");
    const double norm = g.size() == 1 ? g[0].norm() : 0.0;
    if (!(norm > 0.0) || !std::isfinite(norm)) throw py::value_error("state['gamma']: expected a nonzero 3-vector");
    if (!(std::abs(norm - 1.0) <= 1e-12))
      py::module_::import("warnings").attr("warn")("state['gamma']: |gamma| = " + std::to_string(norm) + ", normalised");
    x.R = experiments::attitude_from_gamma(g[0] / norm);
    return x;
  }
  const Array R = Array::ensure(d["R"]);
  if (!R || R.ndim() != 2 || R.shape(0) != 3 || R.shape(1) != 3) throw py::value_error("state['R']: expected a 3x3 array");
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) x.R(r, c) = R.data()[3 * r + c];
  // As the scene files' [initial] matrix: no hidden renormalisation.
  if (!((x.R.transpose() * x.R - lie::Mat3::Identity()).norm() <= 1e-12) || !(std::abs(x.R.determinant() - 1.0) <= 1e-12))
    throw py::value_error("state['R']: not a rotation (|R^T R - I| and |det R - 1| must be <= 1e-12)");
  return x;
}

void bind_indicators(py::module_& m) {
  m.def("indicators", &indicators, py::arg("scene"), py::arg("t_end") = py::none(), py::arg("dt") = py::none(),
        py::arg("states") = py::none(), py::arg("spectrum") = false, py::arg("seed") = 0, py::arg("rtol") = 0.05,
        py::arg("gali") = false, py::arg("gali_samples") = 100, py::arg("gali_spacing") = "log",
        "indicators(scene, t_end=None, dt=None, states=None, spectrum=False, seed=0, rtol=0.05, gali=False,\n"
        "gali_samples=100, gali_spacing='log') -> dict:\n"
        "the records of `lgi indicators` (experiments/INDICATORS.md) as NumPy arrays, one row per state:\n"
        "index, lyapunov (over [0, T]), lyapunov_last_half (over [T/2, T]), megno (<Y>), t_end, converged\n"
        "(0/1: the two exponents agree to rtol, relative), angular_momentum and gamma (n, 3), and with\n"
        "spectrum=True spectrum (n, 6). With gali=True: log10_gali_2 .. log10_gali_6 (at T) and gali, a dict\n"
        "of the file's /gali group (index, t, log10_gali (rows, 5), one row per state and sample time).\n"
        "states: None (the scene's initial state), the path of a state file (HDF5 or CSV, e.g. an lgi\n"
        "equilibria file), or a dict with angular_momentum and gamma ((n, 3)); a Cardan scene takes None\n"
        "only and adds cardan_angles and cardan_momenta (1, 3). t_end and dt default to the scene's [run]\n"
        "values. The GIL is released while it runs.");
  m.def("tangent_flow", &tangent_flow, py::arg("scene"), py::arg("state"), py::arg("v"), py::arg("dt"),
        py::arg("steps") = 1, py::arg("t0") = 0.0,
        "tangent_flow(scene, state, v, dt, steps=1, t0=0.0) -> dict: `steps` RKMK4 steps of size dt of the\n"
        "state with its tangent vectors (integrators/core/tangent_flow.hpp): state is a dict with Pi and R (or\n"
        "gamma), v a 6-vector (xi, dPi) -- the perturbation (R exp(xi^), Pi + dPi) -- or a (6, k) array of k\n"
        "<= 6 vectors as columns. Returns R, Pi, v (same shape as given; not renormalised) and t.");
}

}  // namespace lgi::python
