// lgi.Stepper: a fixed-step scheme advanced one step at a time by the
// caller's loop. Each step is a run of the registered scheme over one step,
// [t0 + k dt, t0 + (k+1) dt], from the current state (the stepper loop's own
// time grid, integrators/core/stepper_loop.hpp), so that n calls of step() take
// the same steps as one run of n steps: bit for bit for every scheme whose
// state is the (R, Pi) it hands back; a scheme that sets up per-run
// constants in start() (the exact flow) sets them up again at every call.
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <ctime>

#include "experiments/cli/simulation.hpp"
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

class Stepper {
 public:
  Stepper(const py::object& scene_arg, const std::string& scheme_name, double dt, double t0)
      : scene_(scene_argument(scene_arg)), scheme_(&scheme_argument(scheme_name)), model_(system::make_model(*scene_)),
        state_(scene_->initial), t0_(t0), t_(t0), dt_(dt) {
    if (scheme_->properties.adaptive)
      throw py::value_error("Stepper: scheme '" + scheme_->name +
                            "' is adaptive; Stepper takes fixed steps (use lgi.simulate with tol=)");
    if (!(dt > 0.0) || !std::isfinite(dt)) throw py::value_error("dt: must be a finite number > 0");
    experiments::check_scheme_supports(*scheme_, *scene_, model_);
  }

  /// Advances n steps (GIL released); RuntimeError with the run's status if a step fails.
  void step(std::int64_t n) {
    if (n < 0) throw py::value_error("n: must be >= 0");
    std::string failure;
    {
      const py::gil_scoped_release release;
      failure = advance(n);
    }
    if (!failure.empty()) throw std::runtime_error(failure);
  }

  py::dict state() const { return state_dict(state_); }
  /// The next step starts from `d` at the current time (t and the step count are kept).
  void set_state(const py::dict& d) { state_ = state_from_dict(d); }

  py::dict stats() const {
    py::dict d;
    d["steps"] = steps_;
    d["rhs_evaluations"] = work_.rhs_evaluations;
    d["rejected_steps"] = work_.rejected_steps;
    d["newton_iterations_max"] = work_.newton_iterations_max;
    d["newton_failures"] = work_.newton_failures;
    d["cpu_seconds"] = cpu_seconds_;
    return d;
  }

  double t() const { return t_; }
  double dt() const { return dt_; }
  std::string scheme() const { return scheme_->name; }

 private:
  std::string advance(std::int64_t n) {
    integrators::NullObserver none;
    const double cpu0 = thread_cpu_seconds();
    std::string failure;
    for (std::int64_t i = 0; i < n; ++i) {
      integrators::RunConfig cfg;
      cfg.t0 = t_;
      cfg.t_end = t0_ + static_cast<double>(steps_ + 1) * dt_;  // the time grid of one long run
      cfg.dt = dt_;
      cfg.cpu_clock = false;
      const integrators::RunStats s = scheme_->run(model_, state_, cfg, none);
      accumulate(s.work);
      if (!s.ok) {
        failure = scheme_->name + " on " + scene_->file + ": " + s.status;
        break;
      }
      ++steps_;
      t_ = cfg.t_end;
    }
    cpu_seconds_ += thread_cpu_seconds() - cpu0;
    return failure;
  }

  void accumulate(const integrators::WorkCounters& w) {
    work_.rhs_evaluations += w.rhs_evaluations;
    work_.rejected_steps += w.rejected_steps;
    work_.newton_failures += w.newton_failures;
    work_.newton_iterations_max = std::max(work_.newton_iterations_max, w.newton_iterations_max);
  }

  std::shared_ptr<const system::Scene> scene_;
  const integrators::SchemeInfo* scheme_;
  system::AnyModel model_;
  system::State state_;
  double t0_, t_, dt_;
  std::int64_t steps_ = 0;
  integrators::WorkCounters work_{};
  double cpu_seconds_ = 0.0;
};

}  // namespace

void bind_stepper(py::module_& m) {
  py::class_<Stepper>(m, "Stepper",
                      "Stepper(scene, scheme, dt, t0=0.0): a fixed-step scheme advanced by your own loop (custom\n"
                      "observers, feedback, coupling to other code). Starts from the scene's initial state at t0.\n"
                      "step(n) takes n steps of the time grid t0 + k dt, each a run of the registered scheme over\n"
                      "one step from the current state: n calls of step() equal lgi.simulate over n steps bit for\n"
                      "bit for schemes that carry no state between steps but (R, Pi); a scheme that sets up\n"
                      "per-run constants (the exact flow) sets them up from the current state at each call.\n"
                      "Adaptive schemes are refused (ValueError): use lgi.simulate(..., tol=...).")
      .def(py::init<const py::object&, const std::string&, double, double>(), py::arg("scene"), py::arg("scheme"),
           py::arg("dt"), py::arg("t0") = 0.0)
      .def("step", &Stepper::step, py::arg("n") = 1,
           "Takes n steps (the GIL is released). RuntimeError with the run's message if a step fails\n"
           "(the state is then the one the failed step left).")
      .def_property("state", &Stepper::state, &Stepper::set_state,
                    "The current state: dict with R (3x3) and Pi (3,), copies. Settable: a dict with Pi and R (a\n"
                    "rotation to 1e-12; ValueError otherwise) or gamma (the vertical in the body frame, the attitude\n"
                    "with the rotation about the vertical fixed as in scene files); t and the step count are kept.")
      .def_property_readonly("t", &Stepper::t, "The current time, t0 + steps * dt.")
      .def_property_readonly("dt", &Stepper::dt)
      .def_property_readonly("scheme", &Stepper::scheme)
      .def_property_readonly("stats", &Stepper::stats,
                             "Totals so far: steps, rhs_evaluations, rejected_steps, newton_iterations_max,\n"
                             "newton_failures, cpu_seconds (thread CPU time inside step()).");
}

}  // namespace lgi::python
