#pragma once
// What a run is given and what it returns: the run configuration, the
// observer that receives samples, and the run statistics. The loop that
// uses them is integrators/core/stepper_loop.hpp.
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "integrators/core/events.hpp"
#include "integrators/core/scheme_interface.hpp"
#include "lie/charts.hpp"

namespace lgi::integrators {

/// Everything a run needs, beyond its configuration, to go on from an
/// accepted step as if it had never stopped (a resumed run's steps are bit
/// for bit those of an uninterrupted one): the step count, t, the state, the
/// work counters, the adaptive loop's next trial step and the scheme's
/// memory between steps (scheme_interface.hpp, "Resume").
template <class S>
struct BasicLoopCheckpoint {
  std::int64_t step = 0;
  double t = 0.0;
  double h = 0.0;  // adaptive runs: the next trial step; fixed-step runs: unused (0)
  S state{};
  WorkCounters work{};
  std::vector<double> memory;  // Scheme::save_memory(); empty for a scheme without memory
};

/// Checkpoints of a run (RunConfig::checkpoints), for a caller that saves
/// them (lgi long-time) and resumes from one. The loop asks due() after
/// every `every`-th accepted step that does not end the run, after the
/// step's samples (and, adaptive, its next trial step); if true, it hands
/// the checkpoint to save(). Schemes that cannot be resumed
/// (resumable_scheme) are never asked. save() may throw: the run ends with
/// the exception.
template <class S>
class BasicCheckpoints {
 public:
  virtual ~BasicCheckpoints() = default;
  virtual bool due(std::int64_t step) = 0;
  virtual void save(const BasicLoopCheckpoint<S>& checkpoint) = 0;
  std::int64_t every = 4096;  // steps between two calls of due() (>= 1)
  /// If set: the run starts from this checkpoint instead of t0 (start() is
  /// still called with the run's initial state, the state passed to the
  /// run, and the initial state is not observed again). A scheme that
  /// cannot be resumed, or a memory it refuses, fails the run.
  const BasicLoopCheckpoint<S>* resume_from = nullptr;
};

using LoopCheckpoint = BasicLoopCheckpoint<State>;  // on SO(3) × ℝ³
using Checkpoints = BasicCheckpoints<State>;

/// Where a crossing inside an adaptive step is located (events.hpp).
enum class EventLocation {
  /// On the scheme's dense output where it has one (the RKMK pairs with an
  /// interpolant: DOP853 and Verner's 6(5), 8(7) and 9(8)), the way Hairer's
  /// DOP853 and OrdinaryDiffEq.jl locate events; on its step map otherwise.
  dense_output,
  /// Always on the scheme's step map: each iteration of the root search is a
  /// step of the scheme from the step's start.
  step_map,
};

/// What a run is asked for, whatever its state space (RunConfig adds the
/// state-typed events and checkpoints).
struct RunSettings {
  double t0 = 0.0;
  double t_end = 0.0;
  double dt = 0.0;            // fixed step, or the first trial step of an adaptive scheme (0: automatic)
  double tol = 0.0;           // adaptive schemes only
  std::int64_t save_every = 1;  // observe every N steps; the initial and final states always
  int retry_halving = 0;      // fixed-step: retry a step whose implicit solve failed as 2, 4, ... substeps, at most N halvings
  /// If set (sorted ascending, within [t0, t_end]): observe exactly at these
  /// times and nowhere else; save_every is ignored (see the top of this file).
  const std::vector<double>* output_times = nullptr;
  /// If set: read once per accepted step; true ends the run after that step
  /// with status "interrupted by signal at step K, t = T" (top of this file).
  const std::atomic<bool>* stop = nullptr;
  /// How an adaptive run locates them (fixed-step runs: always the step map).
  EventLocation event_location = EventLocation::dense_output;
  /// Read the thread CPU clock at the start and end (RunStats::cpu_seconds).
  /// Off, cpu_seconds is 0: a sweep of short trajectories times them itself,
  /// since the clock is a system call (~1 µs) and a short trajectory ~20 µs.
  bool cpu_clock = true;
  /// Schemes on a chart with a singular set (the euler-zxz baselines) stop
  /// before they reach it (baselines/chart_scheme.hpp); false runs them
  /// unguarded, for the singularity study.
  bool chart_guards = true;
  /// Adaptive runs: this many rejections in a row end the run (not ok).
  std::int64_t max_consecutive_rejections = 1000;
};

/// A run on states S (state_space.hpp): its settings, and the events and
/// checkpoints, which see the state.
template <class S>
struct BasicRunConfig : RunSettings {
  /// If set: crossings of these surfaces are located and passed to
  /// Observer::on_event() (top of stepper_loop.hpp).
  const BasicEventFunctions<S>* events = nullptr;
  /// If set: checkpoints are offered to it, and a run may resume from one (Checkpoints).
  BasicCheckpoints<S>* checkpoints = nullptr;
};

/// A run on states S with these settings, and no events or checkpoints yet.
template <class S>
BasicRunConfig<S> run_config_with(const RunSettings& settings) {
  BasicRunConfig<S> cfg;
  static_cast<RunSettings&>(cfg) = settings;
  return cfg;
}

using RunConfig = BasicRunConfig<State>;                    // on SO(3) × ℝ³
using TorusRunConfig = BasicRunConfig<system::TorusState>;  // on T³ × ℝ³ (the Cardan top)

/// Receives the samples of a run on states S. Called once per saved step
/// (never inside the stage loop), so a virtual call costs nothing measurable.
template <class S>
class BasicObserver {
 public:
  virtual ~BasicObserver() = default;
  virtual void observe(std::int64_t step, double t, const S& s) = 0;
  /// Schemes that integrate Euler angles call this right before observe()
  /// with the raw integrated angles (unwrapped), for /particles/body/euler_zxz.
  virtual void observe_euler_zxz(const lie::EulerZXZ& /*angles*/) {}
  /// Called once when the run ends on RunConfig::stop, right before the last
  /// observe() (the state the run ends with). An observer that also watches
  /// the flag itself (to stop loops that do not read RunConfig::stop) knows
  /// from this that the run is ending anyway.
  virtual void on_stop() {}
  /// A located crossing of RunConfig::events, before the observe() of its step.
  virtual void on_event(const BasicEventHit<S>& /*hit*/) {}
};

using Observer = BasicObserver<State>;                    // on SO(3) × ℝ³
using TorusObserver = BasicObserver<system::TorusState>;  // on T³ × ℝ³

/// An observer that keeps nothing.
template <class S>
class BasicNullObserver final : public BasicObserver<S> {
 public:
  void observe(std::int64_t, double, const S&) override {}
};

using NullObserver = BasicNullObserver<State>;

struct RunStats {
  std::int64_t steps = 0;
  WorkCounters work{};
  double cpu_seconds = 0.0;
  double t_final = 0.0;
  bool ok = true;
  std::string status = "ok";  // or the reason the run stopped
  bool interrupted = false;   // the run ended on RunConfig::stop (then ok is false)
};

/// The status of a run ended by RunConfig::stop starts with this.
inline constexpr const char* interrupted_status = "interrupted by signal";

}  // namespace lgi::integrators
