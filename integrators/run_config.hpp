#pragma once
// What a run is given and what it returns: the run configuration, the
// observer that receives samples, and the run statistics. The loop that
// uses them is integrators/stepper_loop.hpp.
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "integrators/events.hpp"
#include "integrators/scheme_interface.hpp"
#include "lie/charts.hpp"

namespace lgi::integrators {

struct RunConfig {
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
  /// If set: crossings of these surfaces are located and passed to
  /// Observer::on_event() (top of this file).
  const EventFunctions* events = nullptr;
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

/// Receives the samples of a run. Called once per saved step (never inside
/// the stage loop), so a virtual call costs nothing measurable.
class Observer {
 public:
  virtual ~Observer() = default;
  virtual void observe(std::int64_t step, double t, const State& s) = 0;
  /// Schemes that integrate Euler angles call this right before observe()
  /// with the raw integrated angles (unwrapped), for /particles/body/euler_zxz.
  virtual void observe_euler_zxz(const lie::EulerZXZ& /*angles*/) {}
  /// Called once when the run ends on RunConfig::stop, right before the last
  /// observe() (the state the run ends with). An observer that also watches
  /// the flag itself (to stop loops that do not read RunConfig::stop) knows
  /// from this that the run is ending anyway.
  virtual void on_stop() {}
  /// A located crossing of RunConfig::events, before the observe() of its step.
  virtual void on_event(const EventHit& /*hit*/) {}
};

/// An observer that keeps nothing.
class NullObserver final : public Observer {
 public:
  void observe(std::int64_t, double, const State&) override {}
};

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
