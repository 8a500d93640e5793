#pragma once
// Separates a run's time into stepping and output: an Observer wrapper that
// adds up the time spent inside the wrapped observer (the invariants, the
// HDF5 writes). RunStats::cpu_seconds covers the whole loop, so stepping =
// cpu_seconds − output_seconds(). The output intervals are read from the
// monotonic clock (about 30 ns a reading through the vDSO) rather than the
// process CPU clock (a system call of about 600 ns on a VM, which at one
// sample a step would cost more than the step it is meant to leave out); the
// process is single-threaded and does not wait on its writes (page cache),
// so the two clocks agree on these intervals.
#include <chrono>

#include "integrators/stepper_loop.hpp"

namespace lgi::experiments {

class OutputTimingObserver final : public integrators::Observer {
 public:
  explicit OutputTimingObserver(integrators::Observer& inner) : inner_(inner) {}

  void observe(std::int64_t step, double t, const system::State& s) override {
    const Clock clock(seconds_);
    inner_.observe(step, t, s);
  }
  void observe_euler_zxz(const lie::EulerZXZ& angles) override {
    const Clock clock(seconds_);
    inner_.observe_euler_zxz(angles);
  }
  void on_stop() override { inner_.on_stop(); }
  double output_seconds() const { return seconds_; }

 private:
  /// Adds the elapsed CPU time on scope exit, also when the observer throws (an interrupt).
  struct Clock {
    explicit Clock(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
    ~Clock() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
    Clock(const Clock&) = delete;
    Clock& operator=(const Clock&) = delete;
    double& total_;
    std::chrono::steady_clock::time_point start_;
  };
  integrators::Observer& inner_;
  double seconds_ = 0.0;
};

}  // namespace lgi::experiments
