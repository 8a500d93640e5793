#pragma once
// One trajectory of a sweep, run through the registry and the one time loop
// (integrators/core/stepper_loop.hpp) on the scene's state space (SO(3) × ℝ³, or
// T³ × ℝ³ for a Cardan scene, docs/cardan.md §7), with an observer that keeps the largest
// invariant errors and the located crossings. Fills one row of /sweep and
// its /events rows (experiments/SWEEPS.md); writes no file.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "experiments/analysis/sweep_plan.hpp"
#include "experiments/io/sweep_file.hpp"  // event_row_width
#include "integrators/ensemble/ensemble_loop.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/system/invariants.hpp"

namespace lgi::experiments {

/// /sweep status codes.
enum SweepStatus : std::int64_t {
  sweep_ok = 0,
  sweep_run_failed = 1,    // the run stopped: a solve, a blow-up, a collapsing step, a refusal
  sweep_setup_failed = 2,  // no initial state (an empty level set) or an invalid varied scene
  sweep_events_truncated = 3,  // ran to t_end, but more than max_events crossings: the first ones kept
};

struct TrajectoryRow {
  std::int64_t index = 0, status = sweep_ok, steps = 0, rejected_steps = 0, event_count = 0, sample_count = 0;
  std::string reason;
  double cpu_seconds = 0.0, t_final = 0.0;  // see SweepRunner::run
  std::array<double, 3> angular_momentum{}, gamma{};
  std::array<double, 4> orientation{};
  std::vector<double> inputs;      // SweepPlan::input_width()
  std::vector<double> max_errors;  // one per SweepRunner::error_names()
  bool interrupted = false;        // ended by the stop flag: not a result
};

/// The per-thread state of a sweep: the current scene and model (rebuilt
/// only when a body or term key changes), the spec's event functions.
class SweepRunner {
 public:
  SweepRunner(const SweepSpec& spec, const SweepPlan& plan, const integrators::SchemeInfo& scheme,
              const integrators::RunConfig& base_config, const std::vector<std::string>& error_names);
  ~SweepRunner();
  SweepRunner(const SweepRunner&) = delete;
  SweepRunner& operator=(const SweepRunner&) = delete;

  /// Runs trajectory i; appends its crossings to `events` (event_row_width
  /// values each). `stop`: the interrupt flag, passed to the loop.
  /// cpu_seconds is the trajectory's time on the monotonic clock (set-up
  /// included); the caller rescales a chunk's rows to its thread CPU time
  /// (scale_to_cpu_time), one system call per chunk instead of two per trajectory.
  /// `row` is overwritten (a caller reuses one row: no allocation per trajectory).
  void run(std::int64_t i, std::vector<double>& events, const std::atomic<bool>* stop, TrajectoryRow& row);

  /// Runs trajectories i, i + 1, … (at most `limit`) and returns how many it
  /// ran; their rows are row(0), row(1), …, their crossings appended to
  /// `events` in index order. Several share one ensemble (docs/ensemble.md)
  /// where the scheme has an ensemble kernel for their scene (and
  /// ensemble::sweep_isa() is set): trajectory i and the following ones
  /// with the same scene, as many as the ensemble has lanes. Each row is the
  /// one run() gives, bit for bit, but cpu_seconds: an ensemble's time is
  /// shared equally by its rows.
  int run_next(std::int64_t i, std::int64_t limit, std::vector<double>& events, const std::atomic<bool>* stop);
  const TrajectoryRow& row(int j) const { return rows_[static_cast<std::size_t>(j)]; }

 private:
  struct Context;
  void prepare(std::int64_t i);
  bool begin_row(std::int64_t i, TrajectoryRow& row, system::State& x);
  void run_timed(std::int64_t i, std::vector<double>& events, const std::atomic<bool>* stop, TrajectoryRow& row);
  void run_cardan(std::int64_t i, std::vector<double>& events, const std::atomic<bool>* stop, TrajectoryRow& row);
  int run_ensemble(std::int64_t i, std::int64_t limit, std::vector<double>& events, const std::atomic<bool>* stop);
  const SweepSpec& spec_;
  const SweepPlan& plan_;
  const integrators::SchemeInfo& scheme_;
  integrators::RunConfig config_;
  std::vector<std::string> error_names_;
  std::unique_ptr<Context> context_;  // the scene, model and invariants in use
  std::vector<double> inputs_;
  std::vector<double> scratch_inputs_;  // the next trajectory's, to compare scenes
  std::vector<double> scratch_;  // invariant errors of one sample
  // The ensemble path (run_next): one row, state, result and event buffer per lane, reused.
  std::vector<TrajectoryRow> rows_;
  std::vector<system::State> states_;
  std::vector<integrators::RunStats> stats_;
  std::vector<std::vector<double>> lane_events_;
  integrators::ensemble::EnsembleWorkspace workspace_;
};

}  // namespace lgi::experiments
