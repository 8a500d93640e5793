#include "experiments/cli/cardan_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "experiments/cli/interrupt_guard.hpp"
#include "experiments/cli/output_grid.hpp"

#include "experiments/cli/run_parameters.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/step_settings.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/number_format.hpp"
#include "experiments/io/scene_suspension.hpp"
#include "lie/quaternion.hpp"

namespace lgi::experiments {
namespace {


constexpr std::size_t cardan_series = 6;  // cardan_angle_1..3, cardan_momentum_1..3

TrajectoryLayout cardan_layout() {
  TrajectoryLayout layout;
  for (int k = 1; k <= 3; ++k) layout.scalar_invariants.push_back({"cardan_angle_" + std::to_string(k), ""});
  for (int k = 1; k <= 3; ++k)
    layout.scalar_invariants.push_back({"cardan_momentum_" + std::to_string(k), "kg m+2 s-1"});
  return layout;
}

/// Samples → the H5MD writer; keeps the energy and p1 errors for the summary line.
class CardanObserver final : public integrators::TorusObserver {
 public:
  CardanObserver(const system::CardanTop& top, TrajectoryWriter* writer) : top_(top), writer_(writer) {}

  void observe(std::int64_t step, double t, const system::TorusState& x) override {
    const double H = top_.energy(x);
    if (!started_) H0_ = H, p10_ = x.p[0], started_ = true;
    const double e = std::abs(H - H0_) / (H0_ != 0.0 ? std::abs(H0_) : 1.0);
    const double m = std::abs(x.p[0] - p10_) / (p10_ != 0.0 ? std::abs(p10_) : 1.0);
    energy_end_ = e, p1_end_ = m;
    if (!(e <= energy_max_)) energy_max_ = e;
    if (!(m <= p1_max_)) p1_max_ = m;
    if (!writer_) return;
    const lie::SO3xR3 body = top_.body_state(x);
    TrajectorySample sample;
    sample.step = step;
    sample.time = t;
    sample.quaternion_wxyz = lie::to_wxyz(lie::quat_from_matrix(body.R));
    sample.angular_momentum_body = body.Pi;
    sample.angular_velocity_body = system::CardanTop::body_rate_matrix(x.q) * top_.velocity(x);
    sample.energy = H;
    sample.invariant_count = cardan_series;
    for (int k = 0; k < 3; ++k) {
      sample.invariants[static_cast<std::size_t>(k)] = x.q[k];
      sample.invariants[static_cast<std::size_t>(k) + 3] = x.p[k];
    }
    sample.orthogonality_error = lie::orthogonality_error(body.R);
    writer_->append(sample);
  }
  /// p1's error only where p1 is an integral (q1 cyclic: a vertical outer axis or no gravity).
  std::string summary() const {
    const std::string energy = "energy_error_end=" + format_sci(energy_end_) + " energy_error_max=" + format_sci(energy_max_);
    if (!top_.outer_angle_cyclic()) return energy + " cardan_momentum_1_conserved=no";
    return energy + " cardan_momentum_1_error_end=" + format_sci(p1_end_) +
           " cardan_momentum_1_error_max=" + format_sci(p1_max_);
  }

 private:
  const system::CardanTop& top_;
  TrajectoryWriter* writer_;
  bool started_ = false;
  double H0_ = 0.0, p10_ = 0.0, energy_end_ = 0.0, energy_max_ = 0.0, p1_end_ = 0.0, p1_max_ = 0.0;
};

}  // namespace

bool is_cardan_scene(const system::Scene& scene) { return scene.suspension.has_value(); }
bool is_cardan_scheme(const std::string& name) { return integrators::find_cardan_scheme(name) != nullptr; }

const integrators::SchemeInfo& scheme_for_scene(const system::Scene& scene, const std::string& name,
                                                const std::string& flag) {
  const integrators::SchemeInfo* torus = integrators::find_cardan_scheme(name);
  if (!is_cardan_scene(scene)) {
    if (torus)
      throw UsageError(flag + ": " + name + " runs on Cardan scenes only (its state is T^3 x R^3; scene " +
                       scene.file + " has no [suspension], its state is SO(3) x R^3)");
    return scheme_by_name(name, flag);
  }
  if (!torus) {
    (void)scheme_by_name(name, flag);  // an unknown name: that error, with the nearest names
    throw UsageError(flag + ": " + name + " runs on SO(3) x R^3 scenes only (scene " + scene.file +
                     " is a Cardan top, state on T^3 x R^3): use cardan-midpoint, cardan-dg, cardan-rk4 or cardan-dp54");
  }
  return *torus;
}

int simulate_cardan(const system::Scene& scene, const std::string& scheme_name, const SimulationRequest& request) {
  SimulationOutcome outcome;
  {
    const InterruptGuard interrupt_guard;
    outcome = run_cardan_simulation(scene, scheme_name, request, &interrupt_requested);
  }
  if (!outcome.stats.ok) {
    std::cerr << "lgi: " << outcome.failure_message << '\n';
    return outcome.stats.interrupted ? interrupted_exit_status() : exit_run_failed;
  }
  if (!request.quiet) {
    const integrators::RunStats& stats = outcome.stats;
    std::cout << "scheme=" << scheme_name << " steps=" << stats.steps << " rejected=" << stats.work.rejected_steps
              << " rhs_evaluations=" << stats.work.rhs_evaluations
              << " cpu_seconds=" << format_sci(outcome.diagnostics.cpu_seconds)
              << " t_end=" << format_general(stats.t_final, 10) << ' ' << outcome.error_summary << '\n';
  }
  return exit_ok;
}

SimulationOutcome run_cardan_simulation(const system::Scene& scene, const std::string& scheme_name,
                                        const SimulationRequest& request, const std::atomic<bool>* stop) {
  const integrators::SchemeInfo& info = scheme_for_scene(scene, scheme_name, "--scheme");
  // The settings as for every scheme; the run on T³ × ℝ³ through the one loop.
  const integrators::RunConfig settings = simulation_config(request, scene, info);
  integrators::TorusRunConfig cfg = integrators::run_config_with<system::TorusState>(settings);
  cfg.stop = stop;
  std::vector<double> times;  // --output-dt's sample times, which cfg points to
  if (request.output_dt) {
    times = output_grid(cfg.t0, cfg.t_end, *request.output_dt);
    cfg.output_times = &times;
  }
  const system::CardanTop top = cardan_top(scene);
  std::optional<TrajectoryWriter> writer;
  if (!request.out.empty()) {
    const ResultAttributes run = run_parameters(scene, info, settings, request.command_line);
    Provenance prov{run.text, run.number, run.integer};
    prov.integer_attributes["save_every"] = cfg.save_every;
    if (request.output_dt) prov.number_attributes["output_dt"] = *request.output_dt;
    if (cfg.retry_halving > 0) prov.integer_attributes["retry_halving"] = cfg.retry_halving;
    writer.emplace(request.out, request.force, cardan_layout(), prov);
  }
  CardanObserver observer(top, writer ? &*writer : nullptr);
  system::TorusState state = scene.cardan_initial;
  SimulationOutcome outcome;
  outcome.stats = info.run_cardan(top, state, cfg, observer);
  if (outcome.stats.interrupted) outcome.stats.status = integrators::interrupted_status;
  outcome.diagnostics = diagnostics_of_run(outcome.stats, 0.0);
  outcome.error_summary = observer.summary();
  close_simulation(outcome, info.name, scene.file, writer ? &*writer : nullptr);
  return outcome;
}

}  // namespace lgi::experiments
