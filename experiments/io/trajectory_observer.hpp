#pragma once
// Turns the states of a run into trajectory samples: invariants through
// SceneInvariants, the attitude as a unit quaternion, then the HDF5 writer.
// Tracks the initial and latest invariant values for the run summary.
#include <atomic>
#include <string>
#include <vector>

#include "experiments/io/h5md_writer.hpp"
#include "integrators/core/stepper_loop.hpp"
#include "integrators/system/invariants.hpp"

namespace lgi::experiments {

/// Set by the SIGINT/SIGTERM handler (InterruptGuard, cli/interrupt_guard.hpp).
/// Commands pass it as RunConfig::stop: the time loop (stepper_loop.hpp, which
/// drives the baselines too) then ends the run after the current step
/// with its statistics and observes its final state (Observer::on_stop()
/// first). No observer throws: a run always returns.
extern std::atomic<bool> interrupt_requested;

/// The file layout for a scene's invariants (units in H5MD spelling).
TrajectoryLayout trajectory_layout(const system::SceneInvariants& invariants, bool euler_zxz = false);

/// A second destination for the samples besides the file: the Python module
/// keeps them in memory (python/). Receives each sample as the writer does,
/// with the state it came from and the invariant errors against the first
/// sample (in the order of SceneInvariants::error_names()).
class SampleSink {
 public:
  virtual ~SampleSink() = default;
  virtual void append(const TrajectorySample& sample, const system::State& state, const std::vector<double>& errors) = 0;
};

class TrajectoryObserver final : public integrators::Observer {
 public:
  /// `writer` and `sink` may each be null (no file; nothing kept in memory).
  TrajectoryObserver(const system::SceneInvariants& invariants, TrajectoryWriter* writer, SampleSink* sink = nullptr)
      : invariants_(invariants), writer_(writer), sink_(sink) {}

  void observe(std::int64_t step, double t, const system::State& s) override;
  void observe_euler_zxz(const lie::EulerZXZ& angles) override { euler_zxz_ = {angles.psi, angles.theta, angles.phi}; }

  bool has_samples() const { return have_initial_; }
  const system::InvariantValues& initial() const { return initial_; }
  const system::InvariantValues& latest() const { return latest_; }
  const system::State& latest_state() const { return latest_state_; }
  double latest_time() const { return latest_time_; }
  /// "name_error_end=value name_error_max=value" pairs (SceneInvariants::
  /// error_names()): the error at the latest sample and the largest over the
  /// observed samples.
  std::string invariant_error_summary() const;

 private:
  const system::SceneInvariants& invariants_;
  TrajectoryWriter* writer_;  // may be null (no file)
  SampleSink* sink_;          // may be null
  bool have_initial_ = false;
  system::InvariantValues initial_{}, latest_{};
  system::State latest_state_{};
  double latest_time_ = 0.0;
  std::vector<double> errors_, errors_max_;  // at the latest sample; largest so far
  std::array<double, 3> euler_zxz_{};  // the last angles a chart-based scheme reported
};

}  // namespace lgi::experiments
