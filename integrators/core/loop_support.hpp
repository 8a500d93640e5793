#pragma once
// The pieces of the time loop (integrators/core/stepper_loop.hpp): the CPU clock,
// failure messages, output times and dense output, event location after a
// step, optional scheme hooks (start, refusal, Euler angles) and the
// fixed-step grid.
#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "integrators/core/run_config.hpp"

namespace lgi::integrators {

namespace detail {
inline double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);  // this thread: sweeps run trajectories on several
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
/// Whether every entry of the state is finite (StateSpace<S>::finite: one
/// branch a step instead of one per entry).
template <class S>
bool finite_state(const S& s) {
  return StateSpace<S>::finite(s);
}
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
/// Two times closer than this are the same output time.
inline double land_tolerance(double t, double span) { return 1e-12 * std::max({1.0, std::abs(t), std::abs(span)}); }
inline bool stop_requested(const RunSettings& cfg) { return cfg.stop && cfg.stop->load(std::memory_order_relaxed); }
inline void mark_interrupted(RunStats& stats, std::int64_t step, double t) {
  stats.ok = false;
  stats.interrupted = true;
  stats.status = failure_message(interrupted_status, step, t, nullptr);
}
/// The output times of cfg.output_times that fall on t (to land_tolerance),
/// One sample; a scheme on Euler angles first reports its raw angles.
template <class Scheme, class S>
void observe_sample(const Scheme& scheme, BasicObserver<S>& observer, std::int64_t step, double t, const S& s) {
  if constexpr (requires { scheme.euler_angles(); }) observer.observe_euler_zxz(scheme.euler_angles());
  observer.observe(step, t, s);
}
/// observed with state s at the output time itself; passed ones are skipped.
/// `next` is the first output time not yet observed or skipped. Returns
/// whether anything was observed.
template <class Scheme, class S>
bool observe_output_times(const Scheme& scheme, const std::vector<double>& times, std::size_t& next, double direction,
                          double span, std::int64_t step, double t, const S& s, BasicObserver<S>& observer) {
  const double tol = land_tolerance(t, span);
  while (next < times.size() && direction * (times[next] - t) < -tol) ++next;
  bool observed = false;
  while (next < times.size() && std::abs(times[next] - t) <= tol) {
    observe_sample(scheme, observer, step, times[next++], s);
    observed = true;
  }
  return observed;
}
/// A scheme with dense output (interpolate()): every output time in
/// [t_start, t] is observed, interpolated inside the step and at the state s
/// at its end (to land_tolerance). Returns whether t itself was observed.
template <class Scheme, class Model, class S>
bool observe_dense(Scheme& scheme, const Model& model, const std::vector<double>& times, std::size_t& next,
                   double span, std::int64_t step, double t_start, double t, const S& s, BasicObserver<S>& observer) {
  const double tol = land_tolerance(t, span);
  bool at_end = false;
  S inside;
  while (next < times.size() && times[next] <= t + tol) {
    const double to = times[next++];
    if (std::abs(to - t) <= tol) {
      observe_sample(scheme, observer, step, to, s);
      at_end = true;
    } else if (to >= t_start) {
      scheme.interpolate(model, to, inside);
      if constexpr (requires { scheme.interpolated_euler_angles(); })
        observer.observe_euler_zxz(scheme.interpolated_euler_angles());
      observer.observe(step, to, inside);
    }
  }
  return at_end;
}
template <class Scheme, class Model>
concept has_dense_output = requires(Scheme& s, const Model& m, state_of<Model>& x) { s.interpolate(m, 0.0, x); };
/// Calls the scheme's start() if it has one; its status if it returns one.
template <class Scheme, class Model, class S>
StepStatus start(Scheme& scheme, const Model& model, const S& s, double t0) {
  if constexpr (requires { { scheme.start(model, s, t0) } -> std::same_as<StepStatus>; }) {
    return scheme.start(model, s, t0);
  } else if constexpr (requires { scheme.start(model, s, t0); }) {
    scheme.start(model, s, t0);
  }
  return {};
}
/// The status of a run whose scheme refused a step (StepStatus::refused).
template <class Scheme>
std::string refusal_message(const Scheme& scheme, std::int64_t step, double t) {
  if constexpr (requires { scheme.refusal_reason(); }) return scheme.refusal_reason();
  else return failure_message("the scheme refused the step", step, t, nullptr);
}
inline void mark_failed(RunStats& stats, std::string why) {
  stats.ok = false;
  stats.status = std::move(why);
}
/// The values of every event function at (t, x), into g (sized here, before the loop).
template <class S>
void event_values(const BasicEventFunctions<S>& events, double t, const S& x, std::vector<double>& g) {
  g.resize(static_cast<std::size_t>(events.count()));
  for (int i = 0; i < events.count(); ++i) g[static_cast<std::size_t>(i)] = events.value(i, t, x);
}
/// After an accepted step (t0, x0) → (t0 + h, x1): locates and reports the
/// crossings in it (events.hpp) and updates g to the values at x1. Returns
/// an empty string, or why a location step failed.
template <class S, class Advance>
std::string report_crossings(const BasicEventFunctions<S>& events, std::vector<double>& g, double t0, double h,
                             const S& x0, const S& x1, std::int64_t step, Advance&& advance,
                             BasicObserver<S>& observer) {
  std::string failure;
  for (int i = 0; i < events.count(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double g1 = events.value(i, t0 + h, x1);
    const int d = crossing_direction(g[k], g1, events.direction(i));
    if (d != 0 && failure.empty()) {
      BasicEventHit<S> hit;
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
concept has_fixed_step =
    requires(Scheme& s, const Model& m, state_of<Model>& x, WorkCounters& w) { s.step(m, x, 0.0, 0.0, w); };
/// A scheme that keeps the attitude itself along a run (the preprocessed DMV
/// on a free body: a quaternion, cayley_quaternion.hpp). The loop steps it
/// with step_keeping_attitude(), which leaves s.R as it was, and has it
/// write R into s with write_attitude() where R is read (stepper_loop.hpp,
/// "Kept attitude"). Its step() is both, for any other caller.
template <class Scheme, class Model>
concept keeps_attitude = requires(Scheme& c, const Scheme& k, const Model& m, State& x, WorkCounters& w) {
  c.step_keeping_attitude(m, x, 0.0, 0.0, w);
  k.write_attitude(x);
};
/// The loop's step: step(), or step_keeping_attitude() for a scheme that keeps the attitude.
template <class Scheme, class Model, class S>
StepStatus loop_step(Scheme& scheme, const Model& model, S& s, double t, double h, WorkCounters& work) {
  if constexpr (keeps_attitude<Scheme, Model>) return scheme.step_keeping_attitude(model, s, t, h, work);
  else return scheme.step(model, s, t, h, work);
}
/// One step of the fixed-step loop, its solve recorded in the work counters.
template <class Scheme, class Model, class S>
StepStatus recorded_step(Scheme& scheme, const Model& model, S& s, double t, double h, WorkCounters& work) {
  const StepStatus st = loop_step(scheme, model, s, t, h, work);
  record_solve(st, work);
  return st;
}
/// One step of size h; while its implicit solve does not converge, it is
/// redone as two steps of h/2, at most `halvings` times deep (RunConfig::
/// retry_halving). Records every attempt: each failed solve counts as a
/// Newton failure and its redone step as a rejected step. Returns the
/// status of the last attempt (not converged if the halvings ran out).
template <class Scheme, class Model, class S>
StepStatus step_with_halving(Scheme& scheme, const Model& model, S& s, double t, double h, int halvings,
                             WorkCounters& work) {
  const S before = s;
  const StepStatus st = loop_step(scheme, model, s, t, h, work);
  record_solve(st, work);
  if (st.converged || halvings <= 0) return st;
  ++work.rejected_steps;
  s = before;
  const StepStatus first = step_with_halving(scheme, model, s, t, 0.5 * h, halvings - 1, work);
  if (!first.converged) return first;
  return step_with_halving(scheme, model, s, t + 0.5 * h, 0.5 * h, halvings - 1, work);
}
/// With events, after the fixed step `step` from (t_start, x_before) to
/// (t, s): writes a kept attitude into s, then locates and reports the
/// crossings (report_crossings) by steps of the scheme as it was before the
/// step, taken as the run's are (with the same halving retries). Returns why
/// a location step failed, or an empty string.
template <class Scheme, class Model, class S>
std::string fixed_step_crossings(Scheme& scheme, const Scheme& scheme_before, const Model& model,
                                 const BasicRunConfig<S>& cfg, std::vector<double>& g, double t_start, double t,
                                 const S& x_before, S& s, std::int64_t step, BasicObserver<S>& observer,
                                 WorkCounters& work) {
  if constexpr (keeps_attitude<Scheme, Model>) scheme.write_attitude(s);
  auto advance = [&](double theta, S& x) {
    Scheme copy = scheme_before;
    x = x_before;
    const bool stepped = cfg.retry_halving > 0
                             ? step_with_halving(copy, model, x, t_start, theta, cfg.retry_halving, work).converged
                             : loop_step(copy, model, x, t_start, theta, work).converged;
    if constexpr (keeps_attitude<Scheme, Model>) copy.write_attitude(x);
    return stepped;
  };
  return report_crossings(*cfg.events, g, t_start, t - t_start, x_before, s, step, advance, observer);
}
/// Where a run is in its output times.
struct OutputCursor {
  const std::vector<double>* times = nullptr;
  std::size_t next = 0;  // the first output time not yet observed or skipped
  double direction = 1.0;
  double span = 0.0;
  std::int64_t next_multiple = 0;  // of save_every, at or after the last step asked about
  /// Whether step k (k ≥ 1, increasing) is a multiple of `every`, by a running
  /// target: one division at the first step (or after a jump), none per step
  /// (a 64-bit division took ~5 ns of dmv's ~60 ns step).
  bool multiple(std::int64_t k, std::int64_t every) {
    if (k < next_multiple) return false;
    if (k > next_multiple) next_multiple = k - k % every;
    const bool due = k == next_multiple;
    next_multiple += every;
    return due;
  }
  /// Whether multiple(k, every) would be true, without moving the target.
  bool multiple_due(std::int64_t k, std::int64_t every) const {
    return k == next_multiple || (k > next_multiple && k % every == 0);
  }
  /// Whether an output time falls on t (observe_output_times would observe one).
  bool output_time_due(double t) const {
    const double tol = land_tolerance(t, span);
    std::size_t i = next;
    while (i < times->size() && direction * ((*times)[i] - t) < -tol) ++i;
    return i < times->size() && std::abs((*times)[i] - t) <= tol;
  }
};
/// A scheme whose loop state is not the trajectory's state
/// (processed_composition.hpp): observers get observable(model, s, work).
template <class Scheme, class Model>
concept has_observable_state = requires(const Scheme& c, const Model& m, const State& x, WorkCounters& w) {
  { c.observable(m, x, w) } -> std::same_as<State>;
};
/// After accepted step k, from t_start to t: the samples due (the output
/// times, else every save_every-th step and the final one), then the stop
/// flag. Returns true if the run ends here, interrupted, with its last state
/// observed once (Observer::on_stop() first).
template <class Scheme, class Model, class S>
bool observe_due(Scheme& scheme, const Model& model, const RunSettings& cfg, OutputCursor& out, std::int64_t k,
                 double t_start, double t, bool final_step, bool stopping, const S& s, BasicObserver<S>& observer,
                 RunStats& stats) {
  if (stopping) observer.on_stop();
  bool observed = false;
  if (out.times) {
    if constexpr (has_dense_output<Scheme, Model>)
      observed = observe_dense(scheme, model, *out.times, out.next, out.span, k, t_start, t, s, observer);
    else
      observed = observe_output_times(scheme, *out.times, out.next, out.direction, out.span, k, t, s, observer);
  } else if (out.multiple(k, cfg.save_every) || final_step) {
    observe_sample(scheme, observer, k, t, s);
    observed = true;
  }
  if (!stopping) return false;
  if (!observed) observe_sample(scheme, observer, k, t, s);
  mark_interrupted(stats, k, t);
  return true;
}
/// The observable state a loop formed last, and after which step (the run's
/// final state reuses it when no step came after: one processor less).
template <class S>
struct FormedObservable {
  S x;
  std::int64_t step = -1;
};
/// Whether observe_due will observe after step k at t.
inline bool sample_due(const RunSettings& cfg, const OutputCursor& out, std::int64_t k, double t, bool final_step,
                       bool stopping) {
  return stopping || (out.times ? out.output_time_due(t) : final_step || out.multiple_due(k, cfg.save_every));
}
/// For a scheme with an observable state, that state is formed only when a
/// sample is due (it costs a processor: processed_composition.hpp), and kept
/// in `formed`; a scheme that keeps the attitude writes it into s then
/// (keeps_attitude: not the ensemble's const scheme, whose lanes' states are formed).
template <class Scheme, class Model, class S>
bool observe_step(Scheme& scheme, const Model& model, const RunSettings& cfg, OutputCursor& out, std::int64_t k,
                  double t_start, double t, bool final_step, S& s, BasicObserver<S>& observer, RunStats& stats,
                  FormedObservable<S>* formed = nullptr) {
  const bool stopping = !final_step && stop_requested(cfg);
  if constexpr (keeps_attitude<Scheme, Model>) {
    if (sample_due(cfg, out, k, t, final_step, stopping)) scheme.write_attitude(s);
  }
  if constexpr (has_observable_state<Scheme, Model>) {
    if (!sample_due(cfg, out, k, t, final_step, stopping)) return false;
    const State x = scheme.observable(model, s, stats.work);
    if (formed) *formed = {x, k};
    return observe_due(scheme, model, cfg, out, k, t_start, t, final_step, stopping, x, observer, stats);
  } else {
    return observe_due(scheme, model, cfg, out, k, t_start, t, final_step, stopping, s, observer, stats);
  }
}
/// The checkpoint the run resumes from (RunConfig::checkpoints), or null.
template <class S>
const BasicLoopCheckpoint<S>* resume_point(const BasicRunConfig<S>& cfg) {
  return cfg.checkpoints ? cfg.checkpoints->resume_from : nullptr;
}
/// Sets the run's state, step count, work counters and the scheme's memory
/// from checkpoint c. False (the run failed, with the reason) if the scheme
/// cannot be resumed or refuses the memory.
template <class Scheme, class Model, bool Adaptive, class S>
bool resume(Scheme& scheme, const BasicLoopCheckpoint<S>& c, S& s, RunStats& stats) {
  if constexpr (!resumable_scheme<Scheme, Model, Adaptive>()) {
    mark_failed(stats, "cannot resume: the scheme keeps memory between steps that it does not save");
    return false;
  } else {
    bool restored = c.memory.empty();
    if constexpr (saves_step_memory<Scheme>) restored = scheme.restore_memory(c.memory);
    if (!restored) {
      mark_failed(stats, "cannot resume: the saved memory does not fit the scheme");
      return false;
    }
    s = c.state;
    stats.steps = c.step;
    stats.work = c.work;
    return true;
  }
}
/// After a resume at t: the output times up to t were observed before it.
inline void skip_output_times(OutputCursor& out, double t) {
  if (!out.times) return;
  const double tol = land_tolerance(t, out.span);
  while (out.next < out.times->size() && out.direction * ((*out.times)[out.next] - t) <= tol) ++out.next;
}
/// Offers the checkpoint after accepted step `step` (not the run's last) to
/// RunConfig::checkpoints, every `every` steps, if the scheme can be resumed.
template <class Scheme, class Model, bool Adaptive, class S>
void offer_checkpoint(const Scheme& scheme, const BasicRunConfig<S>& cfg, std::int64_t step, double t, double h,
                      const S& s, const RunStats& stats) {
  if constexpr (resumable_scheme<Scheme, Model, Adaptive>()) {
    BasicCheckpoints<S>* c = cfg.checkpoints;
    if (c == nullptr || c->every < 1 || step % c->every != 0 || !c->due(step)) return;
    BasicLoopCheckpoint<S> point{.step = step, .t = t, .h = h, .state = s, .work = stats.work, .memory = {}};
    if constexpr (keeps_attitude<Scheme, Model>) scheme.write_attitude(point.state);
    if constexpr (saves_step_memory<Scheme>) scheme.save_memory(point.memory);
    c->save(point);
  }
}
/// The initial sample, and the run's failure if the scheme refused to start.
template <class Scheme, class S>
void observe_start(const Scheme& scheme, const StepStatus& started, double t0, OutputCursor& out, const S& s,
                   BasicObserver<S>& observer, RunStats& stats) {
  if (out.times) observe_output_times(scheme, *out.times, out.next, out.direction, out.span, 0, t0, s, observer);
  else observe_sample(scheme, observer, 0, t0, s);
  if (started.refused) mark_failed(stats, refusal_message(scheme, 0, t0));
}
}  // namespace detail

/// A number in a refusal message: 6 significant digits.
inline std::string format_step_grid_number(double x) {
  std::ostringstream m;
  m.precision(6);
  m << x;
  return m.str();
}

/// The most fixed steps a run takes: 2^53, past which the step index k + 1
/// is no longer exact in a double and t0 + k dt leaves its grid.
inline constexpr std::int64_t max_fixed_steps = std::int64_t{1} << 53;

/// Number of fixed steps covering [t0, t_end]: the nearest integer to
/// span/dt when span is a whole multiple of dt up to 1e-10 relative,
/// otherwise one more step, and the last step ends exactly at t_end. A count
/// above max_fixed_steps (or a NaN ratio) saturates at max_fixed_steps + 1
/// instead of wrapping: fixed_step_grid_problem() names it.
inline std::int64_t fixed_step_count(double span, double dt) {
  if (span <= 0.0) return 0;
  const double ratio = span / dt;
  if (!(ratio <= static_cast<double>(max_fixed_steps))) return max_fixed_steps + 1;
  const double nearest = std::round(ratio);
  if (nearest >= 1.0 && std::abs(ratio - nearest) <= 1e-10 * nearest) return static_cast<std::int64_t>(nearest);
  return static_cast<std::int64_t>(std::ceil(ratio));
}

/// Why the fixed grid t0 + k dt cannot cover [t0, t_end] (either direction),
/// or "" if it can: a step below the resolution of t (t + dt == t at an end
/// of the span: no step would advance time), or more than max_fixed_steps
/// steps. A run with such a grid never starts: it is refused, not reported
/// as a success with zero steps.
inline std::string fixed_step_grid_problem(double t0, double t_end, double dt) {
  if (t_end == t0) return {};
  if (!(dt > 0.0)) return "the step must be > 0";
  if (t0 + dt == t0 || t_end + dt == t_end || t0 - dt == t0 || t_end - dt == t_end)
    return "the step " + format_step_grid_number(dt) + " is below the resolution of t on [" +
           format_step_grid_number(std::min(t0, t_end)) + ", " + format_step_grid_number(std::max(t0, t_end)) +
           "] (t + dt == t)";
  if (fixed_step_count(std::abs(t_end - t0), dt) > max_fixed_steps)
    return "the step " + format_step_grid_number(dt) + " needs more than 2^53 steps over a span of " +
           format_step_grid_number(std::abs(t_end - t0));
  return {};
}

}  // namespace lgi::integrators
