// lgi.simulate(): one run of `lgi simulate` (experiments/cli/simulation.hpp:
// the same run settings, checks, observer and, with out=, the same H5MD
// writer), the samples kept in memory and handed to NumPy without a copy.
#include <pybind11/stl.h>

#include <sstream>

#include "experiments/cli/output_grid.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/simulation.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/h5md_writer.hpp"  // OutputFileError
#include "python/src/bindings.hpp"

namespace lgi::python {
namespace {

using experiments::TrajectorySample;

/// Keeps every sample the observer produces, as the H5MD file has them, plus
/// the attitude matrix and the invariant errors against the first sample.
class SampleRecorder final : public experiments::SampleSink {
 public:
  SampleRecorder(const experiments::TrajectoryLayout& layout, std::size_t error_count, std::size_t expected)
      : layout_(layout), invariants_(layout.scalar_invariants.size()), errors_(error_count) {
    for (auto* v : {&t_, &energy_, &ortho_}) v->reserve(expected);
    step_.reserve(expected);
    R_.reserve(9 * expected);
    q_.reserve(4 * expected);
    Pi_.reserve(3 * expected);
    omega_.reserve(3 * expected);
    for (auto& v : invariants_) v.reserve(expected);
    for (auto& v : errors_) v.reserve(expected);
  }

  void append(const TrajectorySample& s, const system::State& state, const std::vector<double>& errors) override {
    step_.push_back(s.step);
    t_.push_back(s.time);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) R_.push_back(state.R(r, c));  // row-major
    q_.insert(q_.end(), s.quaternion_wxyz.begin(), s.quaternion_wxyz.end());
    for (int i = 0; i < 3; ++i) {
      Pi_.push_back(s.angular_momentum_body[i]);
      omega_.push_back(s.angular_velocity_body[i]);
      if (layout_.space_momentum) m_.push_back(s.angular_momentum_space[i]);
      if (layout_.euler_zxz) euler_.push_back(s.euler_zxz[static_cast<std::size_t>(i)]);
    }
    energy_.push_back(s.energy);
    ortho_.push_back(s.orthogonality_error);
    for (std::size_t k = 0; k < invariants_.size(); ++k) invariants_[k].push_back(s.invariants[k]);
    for (std::size_t k = 0; k < errors_.size() && k < errors.size(); ++k) errors_[k].push_back(errors[k]);
  }

  /// The arrays (the vectors move into NumPy) under the names of lgi.SimulationResult.
  py::dict arrays(const std::vector<std::string>& error_names) && {
    const auto n = static_cast<py::ssize_t>(t_.size());
    py::dict d;
    d["t"] = to_numpy(std::move(t_), {n});
    d["step"] = to_numpy(std::move(step_), {n});
    d["R"] = to_numpy(std::move(R_), {n, 3, 3});
    d["q"] = to_numpy(std::move(q_), {n, 4});
    d["Pi"] = to_numpy(std::move(Pi_), {n, 3});
    d["omega"] = to_numpy(std::move(omega_), {n, 3});
    d["energy"] = to_numpy(std::move(energy_), {n});
    d["orthogonality_error"] = to_numpy(std::move(ortho_), {n});
    d["angular_momentum_space"] = layout_.space_momentum ? py::object(to_numpy(std::move(m_), {n, 3})) : py::none();
    d["euler_zxz"] = layout_.euler_zxz ? py::object(to_numpy(std::move(euler_), {n, 3})) : py::none();
    py::dict invariants, errors;
    for (std::size_t k = 0; k < invariants_.size(); ++k)
      invariants[py::str(layout_.scalar_invariants[k].name)] = to_numpy(std::move(invariants_[k]), {n});
    for (std::size_t k = 0; k < errors_.size() && k < error_names.size(); ++k)
      errors[py::str(error_names[k])] = to_numpy(std::move(errors_[k]), {n});
    d["invariants"] = invariants;
    d["errors"] = errors;
    return d;
  }

 private:
  experiments::TrajectoryLayout layout_;
  std::vector<std::int64_t> step_;
  std::vector<double> t_, R_, q_, Pi_, omega_, energy_, ortho_, m_, euler_;
  std::vector<std::vector<double>> invariants_, errors_;
};

py::dict diagnostics_dict(const experiments::SimulationOutcome& o) {
  const experiments::Diagnostics& d = o.diagnostics;
  py::dict out;
  out["steps"] = d.steps;
  out["rhs_evaluations"] = d.rhs_evaluations;
  out["rejected_steps"] = d.rejected_steps;
  out["newton_iterations_max"] = d.newton_iterations_max;
  out["newton_failures"] = d.newton_failures;
  out["cpu_seconds"] = d.cpu_seconds;
  out["output_seconds"] = d.output_seconds;
  out["t_final"] = o.stats.t_final;
  out["status"] = d.status;
  out["ok"] = o.stats.ok;
  return out;
}

std::string python_call(const system::Scene& scene, const std::string& scheme, const experiments::SimulationRequest& r) {
  std::ostringstream s;
  s.precision(17);
  s << "lgi.simulate(scene='" << scene.file << "', scheme='" << scheme << "'";
  if (r.t_end) s << ", t_end=" << *r.t_end;
  if (r.dt) s << ", dt=" << *r.dt;
  if (r.tol) s << ", tol=" << *r.tol;
  if (r.output_dt) s << ", output_dt=" << *r.output_dt;
  else s << ", save_every=" << r.save_every;
  s << ", out='" << r.out << "')";
  return s.str();
}

/// Samples a run will keep (for reserving): fixed-step runs and output times know it.
std::size_t expected_samples(const integrators::RunConfig& cfg, std::optional<double> output_dt) {
  if (output_dt) return static_cast<std::size_t>(experiments::output_sample_count(cfg.t0, cfg.t_end, *output_dt));
  if (cfg.dt <= 0.0 || cfg.tol > 0.0) return 1024;
  return static_cast<std::size_t>(integrators::fixed_step_count(cfg.t_end - cfg.t0, cfg.dt) / cfg.save_every + 2);
}

py::dict simulate(const py::object& scene_arg, const std::string& scheme_name, std::optional<double> t_end,
                  std::optional<double> dt, std::optional<double> tol, std::int64_t save_every,
                  std::optional<std::string> out, bool force, int retry_halving, std::optional<double> output_dt) {
  const std::shared_ptr<const system::Scene> scene = scene_argument(scene_arg);
  const integrators::SchemeInfo& scheme = scheme_argument(scheme_name);
  if (out && out->empty()) throw experiments::OutputFileError("out: an empty file name");  // as lgi's --out ''
  experiments::SimulationRequest request{dt,    tol,  t_end, save_every, retry_halving, out.value_or(""),
                                         force, true, "",    output_dt};
  if (out) request.command_line = python_call(*scene, scheme.name, request);
  const integrators::RunConfig cfg = experiments::simulation_config(request, *scene, scheme);
  const system::AnyModel model = system::make_model(*scene);
  experiments::check_scheme_supports(scheme, *scene, model);
  const system::SceneInvariants invariants(*scene, model);
  const experiments::TrajectoryLayout layout =
      experiments::trajectory_layout(invariants, scheme.properties.euler_angle_chart);
  SampleRecorder recorder(layout, invariants.error_names().size(), expected_samples(cfg, output_dt));
  experiments::SimulationOutcome outcome;
  {
    const py::gil_scoped_release release;
    outcome = experiments::run_simulation(*scene, scheme, cfg, request, &recorder, nullptr);
  }
  if (!outcome.stats.ok) throw std::runtime_error(outcome.failure_message);
  py::dict result = std::move(recorder).arrays(invariants.error_names());
  result["diagnostics"] = diagnostics_dict(outcome);
  result["scheme"] = scheme.name;
  result["scene"] = scene->name;
  result["out"] = out ? py::object(py::str(*out)) : py::none();
  return result;
}

}  // namespace

const integrators::SchemeInfo& scheme_argument(const std::string& name) {
  return experiments::scheme_by_name(name, "--scheme");
}

void bind_simulate(py::module_& m) {
  m.def("_simulate", &simulate, py::arg("scene"), py::arg("scheme"), py::arg("t_end") = py::none(),
        py::arg("dt") = py::none(), py::arg("tol") = py::none(), py::arg("save_every") = 1,
        py::arg("out") = py::none(), py::arg("force") = false, py::arg("retry_halving") = 0,
        py::arg("output_dt") = py::none(),
        "The compiled part of lgi.simulate: a dict of arrays and diagnostics (see lgi.simulate).");
}

}  // namespace lgi::python
