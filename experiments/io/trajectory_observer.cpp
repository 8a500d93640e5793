#include "experiments/io/trajectory_observer.hpp"

#include <cstdio>
#include <sstream>

#include "experiments/io/number_format.hpp"
#include "lie/quaternion.hpp"

namespace lgi::experiments {

std::atomic<bool> interrupt_requested{false};

TrajectoryLayout trajectory_layout(const system::SceneInvariants& invariants, bool euler_zxz) {
  TrajectoryLayout layout;
  for (const auto& name : invariants.scalar_names()) {
    const std::string unit = name == "kovalevskaya_k" ? "s-4" : name == "casimir_field_momentum" ? "kg m+2 s-1 T" : "kg m+2 s-1";
    layout.scalar_invariants.push_back({name, unit});
  }
  layout.space_momentum = invariants.free_body();
  layout.euler_zxz = euler_zxz;
  return layout;
}

void TrajectoryObserver::observe(std::int64_t step, double t, const system::State& s) {
  latest_ = invariants_.evaluate(s);
  latest_state_ = s;
  latest_time_ = t;
  if (!have_initial_) {
    initial_ = latest_;
    have_initial_ = true;
  }
  invariants_.errors(initial_, latest_, errors_);
  errors_max_.resize(errors_.size(), 0.0);
  for (std::size_t k = 0; k < errors_.size(); ++k)
    if (!(errors_[k] <= errors_max_[k])) errors_max_[k] = errors_[k];  // NaN propagates
  if (!writer_ && !sink_) return;
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
  if (writer_) writer_->append(sample);
  if (sink_) sink_->append(sample, s, errors_);
}

std::string TrajectoryObserver::invariant_error_summary() const {
  const std::vector<std::string> names = invariants_.error_names();
  std::string out;
  for (std::size_t k = 0; k < names.size() && k < errors_.size(); ++k) {
    if (k) out += ' ';
    out += names[k] + "_error_end=" + format_sci(errors_[k]) + ' ' + names[k] + "_error_max=" + format_sci(errors_max_[k]);
  }
  return out;
}

}  // namespace lgi::experiments
