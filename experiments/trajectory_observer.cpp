#include "experiments/trajectory_observer.hpp"

#include <cstdio>
#include <sstream>

#include "experiments/number_format.hpp"
#include "lie/quaternion.hpp"

namespace lgi::experiments {

std::atomic<bool> interrupt_requested{false};

TrajectoryLayout trajectory_layout(const system::SceneInvariants& invariants, bool euler_zxz) {
  TrajectoryLayout layout;
  for (const auto& name : invariants.scalar_names()) {
    const std::string unit = name == "kovalevskaya_k" ? "s-4" : "kg m+2 s-1";
    layout.scalar_invariants.push_back({name, unit});
  }
  layout.space_momentum = invariants.free_body();
  layout.euler_zxz = euler_zxz;
  return layout;
}

void TrajectoryObserver::observe(std::int64_t step, double t, const system::State& s) {
  if (interrupt_requested.load(std::memory_order_relaxed)) throw Interrupted("interrupted by signal");
  latest_ = invariants_.evaluate(s);
  latest_state_ = s;
  latest_time_ = t;
  if (!have_initial_) {
    initial_ = latest_;
    have_initial_ = true;
    errors_max_.assign(invariant_error_names().size(), 0.0);
  }
  const std::vector<double> errors = invariant_errors(latest_);
  for (std::size_t k = 0; k < errors.size(); ++k)
    if (!(errors[k] <= errors_max_[k])) errors_max_[k] = errors[k];  // NaN propagates
  if (!writer_) return;
  TrajectorySample sample;
  sample.step = step;
  sample.time = t;
  sample.quaternion_wxyz = lie::to_wxyz(lie::quat_from_matrix(s.R));
  sample.angular_momentum_body = s.Pi;
  sample.angular_velocity_body = invariants_.omega(s);
  sample.energy = latest_.energy;
  sample.angular_momentum_space = latest_.space_momentum;
  sample.invariant_count = invariants_.scalar_names().size();
  for (std::size_t k = 0; k < sample.invariant_count; ++k) sample.invariants[k] = latest_.scalars[k];
  sample.orthogonality_error = latest_.orthogonality_error;
  sample.euler_zxz = euler_zxz_;
  writer_->append(sample);
}

std::vector<std::string> TrajectoryObserver::invariant_error_names() const {
  std::vector<std::string> names;
  if (invariants_.energy_conserved()) names.push_back("energy_error");
  for (const auto& n : invariants_.scalar_names()) names.push_back(n + "_error");
  if (invariants_.free_body()) names.push_back("angular_momentum_space_error");
  names.push_back("orthogonality_error");
  return names;
}

std::vector<double> TrajectoryObserver::invariant_errors(const system::InvariantValues& v) const {
  std::vector<double> e;
  if (invariants_.energy_conserved()) e.push_back(system::relative_error(v.energy, initial_.energy));
  for (std::size_t k = 0; k < invariants_.scalar_names().size(); ++k)
    e.push_back(system::relative_error(v.scalars[k], initial_.scalars[k]));
  if (invariants_.free_body()) {
    const double m0 = initial_.space_momentum.norm();
    const double d = (v.space_momentum - initial_.space_momentum).norm();
    e.push_back(m0 > 0.0 ? d / m0 : d);
  }
  e.push_back(v.orthogonality_error);
  return e;
}

std::string TrajectoryObserver::invariant_error_summary() const {
  const std::vector<std::string> names = invariant_error_names();
  const std::vector<double> end = invariant_errors(latest_);
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (k) out += ' ';
    out += names[k] + "_end=" + format_sci(end[k]) + ' ' + names[k] + "_max=" + format_sci(errors_max_[k]);
  }
  return out;
}

}  // namespace lgi::experiments
