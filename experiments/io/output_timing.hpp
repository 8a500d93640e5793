#pragma once
// Separates a run's time into stepping and output: an Observer wrapper that
// adds up the time spent inside the wrapped observer (the invariants, the
// HDF5 writes). RunStats::cpu_seconds covers the whole loop, so stepping =
// cpu_seconds − output_cpu_seconds(cpu_seconds).
//
// The output intervals are read from the monotonic clock (about 30 ns a
// reading through the vDSO) rather than the thread CPU clock (a system call
// of about 600 ns on a VM, which at one sample a step would cost more than
// the step it is meant to leave out). On a loaded machine the wall-clock
// intervals also hold the time the thread waited for a core, so they are
// converted to CPU time with the share of a core the thread got over the
// whole run, cpu / wall (1 on an idle machine). Subtracting the raw wall
// intervals instead left a stepping time of 0 on a machine shared with a
// build. The stepping time is then cpu × (1 − output_wall / run_wall): never
// negative, and exact when the load is even over the run.
#include <algorithm>
#include <chrono>

#include "integrators/core/stepper_loop.hpp"

namespace lgi::experiments {

/// On states S (integrators/core/state_space.hpp).
template <class S>
class BasicOutputTimingObserver final : public integrators::BasicObserver<S> {
 public:
  /// The run's wall clock starts here: construct it just before the loop.
  explicit BasicOutputTimingObserver(integrators::BasicObserver<S>& inner)
      : inner_(inner), run_start_(std::chrono::steady_clock::now()) {}

  void observe(std::int64_t step, double t, const S& s) override {
    const Clock clock(wall_seconds_);
    inner_.observe(step, t, s);
  }
  void observe_euler_zxz(const lie::EulerZXZ& angles) override {
    const Clock clock(wall_seconds_);
    inner_.observe_euler_zxz(angles);
  }
  void on_event(const integrators::BasicEventHit<S>& hit) override {
    const Clock clock(wall_seconds_);
    inner_.on_event(hit);
  }
  void on_stop() override { inner_.on_stop(); }

  /// Wall-clock seconds spent in the wrapped observer so far.
  double output_wall_seconds() const { return wall_seconds_; }

  /// The output's share of run_cpu_seconds, the thread CPU time since
  /// construction: the output's wall time times the share of a core the
  /// thread got over the run (at most 1).
  double output_cpu_seconds(double run_cpu_seconds) const {
    const double run_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start_).count();
    if (!(run_wall > 0.0) || !(run_cpu_seconds > 0.0)) return 0.0;
    return wall_seconds_ * std::min(1.0, run_cpu_seconds / run_wall);
  }

 private:
  /// Adds the elapsed wall time on scope exit, also when the observer throws (an interrupt).
  struct Clock {
    explicit Clock(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
    ~Clock() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
    Clock(const Clock&) = delete;
    Clock& operator=(const Clock&) = delete;
    double& total_;
    std::chrono::steady_clock::time_point start_;
  };
  integrators::BasicObserver<S>& inner_;
  std::chrono::steady_clock::time_point run_start_;
  double wall_seconds_ = 0.0;
};

using OutputTimingObserver = BasicOutputTimingObserver<system::State>;

}  // namespace lgi::experiments
