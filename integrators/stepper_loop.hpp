#pragma once
// The stepper loop: drives a scheme over [t0, t_end] and hands samples to
// an observer. It owns the step count, the time grid, the checks that stop
// a run (non-finite state, an implicit solve that did not converge, a
// collapsing adaptive step) and the CPU clock. It knows no file format.
//
// Output times (RunConfig::output_times): observe exactly at these times and
// nowhere else, with the rule of the baselines (baselines/runner.hpp,
// BaselineOptions::output_times). Fixed-step runs keep their grid t0 + k dt
// (no step is shortened) and observe the output times that coincide with a
// grid time to 1e-12 max(1, |t|, |t_end - t0|); the others are skipped.
// Adaptive runs shorten the step that would pass the next output time so as
// to land on it exactly; the controller's proposal for the following step is
// not shortened (the larger of the proposal and the step that was tried).
// Several samples may share a step number; the sample's time is the output
// time itself.
//
// Stop flag (RunConfig::stop): read once per accepted step. When it is set,
// the run ends after that step (unless the step reached t_end: then the run
// is complete) with ok = false, interrupted = true and status
// "interrupted by signal at step K, t = T"; the state after the step is the
// final state and is observed once (Observer::on_stop() first, then
// observe(), unless that step was observed anyway), so the last sample is kept.
// steps, work, cpu_seconds and t_final are filled as for any other run.
//
// Events (RunConfig::events): after every accepted step the loop evaluates
// the event functions and locates each crossing on the scheme's own step map
// (events.hpp), then hands it to Observer::on_event() before the step's
// observe(). Crossings in one step are reported in the order of the event
// functions. The run's steps and states are the same with or without events;
// the location steps add to WorkCounters::rhs_evaluations only (they are
// taken as the run's steps are, with the same halving retries). A location
// step whose implicit solve fails, or that leaves a non-finite state, ends
// the run (not ok, status "event location failed ...").
//
// With all three null, the loop is the one it always was: the same steps,
// the same arithmetic and the same observe() calls.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <optional>
#include <sstream>
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

namespace detail {
inline double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);  // this thread: sweeps run trajectories on several
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
inline bool finite_state(const State& s) { return s.R.allFinite() && s.Pi.allFinite(); }
inline void record_solve(const StepStatus& st, WorkCounters& work) {
  if (st.iterations > work.newton_iterations_max) work.newton_iterations_max = st.iterations;
  if (!st.converged) ++work.newton_failures;
}
inline std::string failure_message(const char* what, std::int64_t step, double t, const StepStatus* st) {
  std::ostringstream m;
  m.precision(17);
  m << what << " at step " << step << ", t = " << t;
  if (st) m << " (" << st->iterations << " iterations, residual " << st->residual << ")";
  return m.str();
}
/// Two times closer than this are the same output time (as the baselines' land_tolerance).
inline double land_tolerance(double t, double span) { return 1e-12 * std::max({1.0, std::abs(t), std::abs(span)}); }
inline bool stop_requested(const RunConfig& cfg) { return cfg.stop && cfg.stop->load(std::memory_order_relaxed); }
inline void mark_interrupted(RunStats& stats, std::int64_t step, double t) {
  stats.ok = false;
  stats.interrupted = true;
  stats.status = failure_message(interrupted_status, step, t, nullptr);
}
/// The output times of cfg.output_times that fall on t (to land_tolerance),
/// observed with state s at the output time itself; passed ones are skipped.
/// `next` is the first output time not yet observed or skipped. Returns
/// whether anything was observed.
inline bool observe_output_times(const std::vector<double>& times, std::size_t& next, double direction, double span,
                                 std::int64_t step, double t, const State& s, Observer& observer) {
  const double tol = land_tolerance(t, span);
  while (next < times.size() && direction * (times[next] - t) < -tol) ++next;
  bool observed = false;
  while (next < times.size() && std::abs(times[next] - t) <= tol) {
    observer.observe(step, times[next++], s);
    observed = true;
  }
  return observed;
}
/// The values of every event function at (t, x), into g (sized here, before the loop).
inline void event_values(const EventFunctions& events, double t, const State& x, std::vector<double>& g) {
  g.resize(static_cast<std::size_t>(events.count()));
  for (int i = 0; i < events.count(); ++i) g[static_cast<std::size_t>(i)] = events.value(i, t, x);
}
/// After an accepted step (t0, x0) → (t0 + h, x1): locates and reports the
/// crossings in it (events.hpp) and updates g to the values at x1. Returns
/// an empty string, or why a location step failed.
template <class Advance>
std::string report_crossings(const EventFunctions& events, std::vector<double>& g, double t0, double h,
                             const State& x0, const State& x1, std::int64_t step, Advance&& advance,
                             Observer& observer) {
  std::string failure;
  for (int i = 0; i < events.count(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double g1 = events.value(i, t0 + h, x1);
    const int d = crossing_direction(g[k], g1, events.direction(i));
    if (d != 0 && failure.empty()) {
      EventHit hit;
      hit.event = i;
      hit.direction = d;
      hit.step = step;
      if (!locate_crossing(events, i, t0, h, x0, x1, g[k], g1, advance, hit))
        failure = failure_message(
            "event location failed: a step of the root search did not succeed (no convergence, or a non-finite state)",
            step, t0 + h, nullptr);
      observer.on_event(hit);
    }
    g[k] = g1;
  }
  return failure;
}
template <class Scheme, class Model>
concept has_fixed_step = requires(Scheme& s, const Model& m, State& x, WorkCounters& w) { s.step(m, x, 0.0, 0.0, w); };
template <class Scheme, class Model>
concept has_start = requires(Scheme& s, const Model& m, const State& x) { s.start(m, x, 0.0); };
/// One step of size h; while its implicit solve does not converge, it is
/// redone as two steps of h/2, at most `halvings` times deep (RunConfig::
/// retry_halving). Records every attempt: each failed solve counts as a
/// Newton failure and its redone step as a rejected step. Returns the
/// status of the last attempt (not converged if the halvings ran out).
template <class Scheme, class Model>
StepStatus step_with_halving(Scheme& scheme, const Model& model, State& s, double t, double h, int halvings,
                             WorkCounters& work) {
  const State before = s;
  const StepStatus st = scheme.step(model, s, t, h, work);
  record_solve(st, work);
  if (st.converged || halvings <= 0) return st;
  ++work.rejected_steps;
  s = before;
  const StepStatus first = step_with_halving(scheme, model, s, t, 0.5 * h, halvings - 1, work);
  if (!first.converged) return first;
  return step_with_halving(scheme, model, s, t + 0.5 * h, 0.5 * h, halvings - 1, work);
}
}  // namespace detail

/// Number of fixed steps covering [t0, t_end]: the nearest integer to
/// span/dt when span is a whole multiple of dt up to 1e-10 relative,
/// otherwise one more step, and the last step ends exactly at t_end.
inline std::int64_t fixed_step_count(double span, double dt) {
  if (span <= 0.0) return 0;
  const double ratio = span / dt;
  const double nearest = std::round(ratio);
  if (nearest >= 1.0 && std::abs(ratio - nearest) <= 1e-10 * nearest) return static_cast<std::int64_t>(nearest);
  return static_cast<std::int64_t>(std::ceil(ratio));
}

/// Fixed-step run. Step k covers [t0 + k h, t0 + (k+1) h] (times are
/// computed, not accumulated); the last step is clipped to t_end. If
/// t_end < t0 the run goes backward in time with steps of −dt (used to check
/// the symmetry Φ₋ₕ ∘ Φₕ = id through the registry).
template <class Scheme, class Model>
RunStats integrate_fixed(Scheme& scheme, const Model& model, State& s, const RunConfig& cfg, Observer& observer) {
  RunStats stats;
  const double cpu0 = cfg.cpu_clock ? detail::cpu_now() : 0.0;
  if constexpr (detail::has_start<Scheme, Model>) scheme.start(model, s, cfg.t0);
  const double direction = cfg.t_end < cfg.t0 ? -1.0 : 1.0;
  const std::int64_t n = fixed_step_count(direction * (cfg.t_end - cfg.t0), cfg.dt);
  const std::vector<double>* times = cfg.output_times;
  const double span = cfg.t_end - cfg.t0;
  std::size_t next = 0;
  if (times) detail::observe_output_times(*times, next, direction, span, 0, cfg.t0, s, observer);
  else observer.observe(0, cfg.t0, s);
  double t = cfg.t0;
  const EventFunctions* events = cfg.events;
  std::vector<double> g;
  std::optional<Scheme> scheme_before;  // with events: the scheme as it was before the step
  State x_before;
  if (events) detail::event_values(*events, cfg.t0, s, g);
  for (std::int64_t k = 0; k < n; ++k) {
    const double t_next = k + 1 == n ? cfg.t_end : cfg.t0 + direction * static_cast<double>(k + 1) * cfg.dt;
    if (events) {
      scheme_before.emplace(scheme);
      x_before = s;
    }
    StepStatus st;
    if (cfg.retry_halving > 0) {
      st = detail::step_with_halving(scheme, model, s, t, t_next - t, cfg.retry_halving, stats.work);
    } else {
      st = scheme.step(model, s, t, t_next - t, stats.work);
      detail::record_solve(st, stats.work);
    }
    stats.steps = k + 1;
    if (!st.converged) {
      stats.ok = false;
      stats.status =
          detail::failure_message(st.reason ? st.reason : "implicit solve did not converge", k + 1, t_next, &st);
      if (cfg.retry_halving > 0) stats.status += " after " + std::to_string(cfg.retry_halving) + " halvings of the step";
      break;
    }
    if (!detail::finite_state(s)) {
      stats.ok = false;
      stats.status = detail::failure_message("state became non-finite (blow-up)", k + 1, t_next, nullptr);
      break;
    }
    if (events) {
      const double t_start = t;
      // The search's steps are taken as the run's are (with the same halving retries).
      auto advance = [&](double theta, State& x) {
        Scheme copy = *scheme_before;
        x = x_before;
        if (cfg.retry_halving > 0)
          return detail::step_with_halving(copy, model, x, t_start, theta, cfg.retry_halving, stats.work).converged;
        return copy.step(model, x, t_start, theta, stats.work).converged;
      };
      std::string why = detail::report_crossings(*events, g, t, t_next - t, x_before, s, k + 1, advance, observer);
      if (!why.empty()) {
        stats.ok = false;
        stats.status = std::move(why);
        t = t_next;
        break;
      }
    }
    t = t_next;
    const bool stopping = k + 1 < n && detail::stop_requested(cfg);
    if (stopping) observer.on_stop();
    bool observed = false;
    if (times) {
      observed = detail::observe_output_times(*times, next, direction, span, k + 1, t, s, observer);
    } else if ((k + 1) % cfg.save_every == 0 || k + 1 == n) {
      observer.observe(k + 1, t, s);
      observed = true;
    }
    if (stopping) {
      if (!observed) observer.observe(k + 1, t, s);
      detail::mark_interrupted(stats, k + 1, t);
      break;
    }
  }
  stats.t_final = t;
  stats.cpu_seconds = cfg.cpu_clock ? detail::cpu_now() - cpu0 : 0.0;
  return stats;
}

/// Adaptive run: accepted steps advance, rejected ones retry with the
/// proposed smaller step. The run stops (status not ok) if the step falls
/// below 1e-14·max(1, |t|): the error target cannot be met in double precision.
template <class Scheme, class Model>
RunStats integrate_adaptive(Scheme& scheme, const Model& model, State& s, const RunConfig& cfg, Observer& observer) {
  RunStats stats;
  const double cpu0 = cfg.cpu_clock ? detail::cpu_now() : 0.0;
  if constexpr (detail::has_start<Scheme, Model>) scheme.start(model, s, cfg.t0);
  const std::vector<double>* times = cfg.output_times;
  const double span = cfg.t_end - cfg.t0;
  std::size_t next = 0;
  if (times) detail::observe_output_times(*times, next, 1.0, span, 0, cfg.t0, s, observer);
  else observer.observe(0, cfg.t0, s);
  double t = cfg.t0;
  double h = cfg.dt > 0.0 ? std::min(cfg.dt, span) : scheme.initial_step(model, s, t, span);
  std::int64_t k = 0;
  const EventFunctions* events = cfg.events;
  std::vector<double> g;
  std::optional<Scheme> scheme_before;  // with events: the scheme as it was before the attempt
  if (events) detail::event_values(*events, cfg.t0, s, g);
  while (span > 0.0 && t < cfg.t_end) {
    // The time this step may not pass: t_end, or the next output time before it.
    double target = cfg.t_end;
    double land = 1e-12 * std::abs(cfg.t_end);
    if (times && next < times->size() && (*times)[next] < cfg.t_end) {
      target = (*times)[next];
      land = detail::land_tolerance(target, span);
    }
    const bool last = t + h >= target || (target - (t + h)) < land;
    const double h_try = last ? target - t : h;
    const State before = s;
    if (events) scheme_before.emplace(scheme);
    const AdaptiveStatus a = scheme.attempt(model, s, t, h_try, stats.work);
    detail::record_solve(a.solve, stats.work);
    if (!a.accepted) {
      s = before;
      h = a.h_next;
      if (!(h >= 1e-14 * std::max(1.0, std::abs(t)))) {
        stats.ok = false;
        stats.status = detail::failure_message("adaptive step size collapsed below 1e-14", k, t, nullptr);
        break;
      }
      continue;
    }
    ++k;
    const double t_start = t;
    t = last ? target : t + h_try;
    stats.steps = k;
    if (!detail::finite_state(s)) {
      stats.ok = false;
      stats.status = detail::failure_message("state became non-finite (blow-up)", k, t, nullptr);
      break;
    }
    if (events) {
      // The search takes steps of the pair's propagated solution whatever its
      // error estimate says (a step no longer than an accepted one): step(),
      // the forced attempt. A scheme without step() can only offer its
      // accepted attempts, so a rejected trial there ends the search.
      auto advance = [&](double theta, State& x) {
        Scheme copy = *scheme_before;
        x = before;
        if constexpr (detail::has_fixed_step<Scheme, Model>) {
          return copy.step(model, x, t_start, theta, stats.work).converged;
        } else {
          const AdaptiveStatus tried = copy.attempt(model, x, t_start, theta, stats.work);
          return tried.accepted && tried.solve.converged;
        }
      };
      std::string why = detail::report_crossings(*events, g, t_start, t - t_start, before, s, k, advance, observer);
      if (!why.empty()) {
        stats.ok = false;
        stats.status = std::move(why);
        break;
      }
    }
    const bool stopping = t < cfg.t_end && detail::stop_requested(cfg);
    if (stopping) observer.on_stop();
    bool observed = false;
    if (times) {
      observed = detail::observe_output_times(*times, next, 1.0, span, k, t, s, observer);
    } else if (k % cfg.save_every == 0 || t >= cfg.t_end) {
      observer.observe(k, t, s);
      observed = true;
    }
    if (stopping) {
      if (!observed) observer.observe(k, t, s);
      detail::mark_interrupted(stats, k, t);
      break;
    }
    // A step shortened to land on an output time (or t_end, which ends the
    // run) does not shrink the next proposal (as the baselines).
    h = last ? std::max(a.h_next, h) : a.h_next;
  }
  stats.t_final = t;
  stats.cpu_seconds = cfg.cpu_clock ? detail::cpu_now() - cpu0 : 0.0;
  return stats;
}

}  // namespace lgi::integrators
