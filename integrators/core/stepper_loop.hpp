#pragma once
// The one time loop: drives every scheme, the Lie-group schemes and the
// baselines (baselines/chart_scheme.hpp) alike, over [t0, t_end] and hands
// samples to an observer. It owns the step count, the time grid, the checks
// that stop a run (non-finite state, an implicit solve that did not
// converge, a step the scheme refused, a collapsing adaptive step, too many
// rejections in a row) and the CPU clock. It knows no file format.
//
// State spaces: the loop is a template on the state type S (state_space.hpp):
// system::State on SO(3) × ℝ³, system::TorusState on T³ × ℝ³ (the Cardan
// top, docs/cardan.md §7), one compiled loop per (scheme, model, state).
// RunConfig, Observer, EventFunctions, EventHit and LoopCheckpoint are the
// SO(3) instances of BasicRunConfig<S>, BasicObserver<S>, ...; TorusRunConfig
// and TorusObserver the T³ ones. Everything below holds on both.
//
// Output times (RunConfig::output_times): observe exactly at these times and
// nowhere else. Fixed-step runs keep their grid t0 + k dt
// (no step is shortened) and observe the output times that coincide with a
// grid time to 1e-12 max(1, |t|, |t_end - t0|); the others are skipped.
// Adaptive runs shorten the step that would pass the next output time so as
// to land on it exactly; the controller's proposal for the following step is
// not shortened (the larger of the proposal and the step that was tried).
// A scheme with dense output (dopri5) is not shortened: the output times
// inside a step are interpolated, and one at the step's end is its state.
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
// the event functions and locates each crossing (events.hpp): on the
// scheme's dense output if it has one (and RunConfig::event_location is
// dense_output, the default), else on its own step map. It then hands the
// crossing to Observer::on_event() before the step's observe(). Crossings in
// one step are reported in the order of the event functions. The run's
// steps and states are the same with or without events; the location steps
// (or the interpolant's extra stages) add to WorkCounters::rhs_evaluations
// only (location steps are taken as the run's steps are, with the same
// halving retries). A location step whose implicit solve fails, or that
// leaves a non-finite state, ends the run (not ok, status "event location
// failed ...").
//
// Checkpoints (RunConfig::checkpoints, run_config.hpp): every `every`-th
// accepted step that does not end the run, a scheme that can be resumed
// (scheme_interface.hpp, "Resume") offers its LoopCheckpoint after the
// step's samples. A run given resume_from calls start() with the state it is
// passed (the run's initial state), then goes on from the checkpoint's step,
// t, state, work counters, scheme memory and (adaptive) trial step, without
// observing the initial state again: its steps, samples and counters are bit
// for bit those of the uninterrupted run from there on.
//
// Observable state (a processed composition, processed_composition.hpp): the
// loop steps the scheme's own variable and hands observers, and the caller at
// the end, scheme.observable(model, s, work), formed only when a sample is due.
// Checkpoints hold the loop's variable and the scheme's memory. Such a scheme
// locates no events: a run given event functions fails before its first step.
//
// With all four null, the loop is the one it always was: the same steps,
// the same arithmetic and the same observe() calls.
//
// Kept attitude (detail::keeps_attitude; the preprocessed DMV on a free body,
// integrators/schemes/cayley_quaternion.hpp): the scheme carries the attitude as a
// quaternion q, and the loop steps it with step_keeping_attitude(), which
// advances Π and q and leaves s.R as it was. The loop has R = R(q) written
// into s wherever R is read: before a sample (observe_step), after every
// step of a run with events (and after each step of their search), into a
// checkpoint's state, and at the run's end, whatever ended it. The check for
// a non-finite state reads s as it is, the new Π and the R last written: q
// is non-finite only if the initial R was (then so is the R the check reads)
// or if the Cayley parameter was, which makes Π non-finite in the same step.
// The run's steps, samples and final state are those of step() at every
// step (step() = step_keeping_attitude() + write_attitude();
// tests/test_kept_attitude.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "integrators/core/loop_support.hpp"
#include "integrators/core/run_config.hpp"

namespace lgi::integrators {

/// Fixed-step run. Step k covers [t0 + k h, t0 + (k+1) h] (times are
/// computed, not accumulated); the last step is clipped to t_end. If
/// t_end < t0 the run goes backward in time with steps of −dt (used to check
/// the symmetry Φ₋ₕ ∘ Φₕ = id through the registry).
template <class Scheme, class Model, class S>
RunStats integrate_fixed(Scheme& scheme, const Model& model, S& s, const BasicRunConfig<S>& cfg,
                         BasicObserver<S>& observer) {
  RunStats stats;
  const double cpu0 = cfg.cpu_clock ? detail::cpu_now() : 0.0;
  const StepStatus started = detail::start(scheme, model, s, cfg.t0);
  const double direction = cfg.t_end < cfg.t0 ? -1.0 : 1.0;
  const std::string grid_problem = fixed_step_grid_problem(cfg.t0, cfg.t_end, cfg.dt);
  const std::int64_t n =
      started.refused || !grid_problem.empty() ? 0 : fixed_step_count(direction * (cfg.t_end - cfg.t0), cfg.dt);
  detail::OutputCursor out{.times = cfg.output_times, .direction = direction, .span = cfg.t_end - cfg.t0};
  double t = cfg.t0;
  std::int64_t first = 0;
  if (const BasicLoopCheckpoint<S>* from = detail::resume_point(cfg); from && !started.refused) {
    first = n;  // unless the resume succeeds
    if (detail::resume<Scheme, Model, false>(scheme, *from, s, stats)) first = from->step, t = from->t;
    detail::skip_output_times(out, t);
  } else {
    detail::observe_start(scheme, started, cfg.t0, out, s, observer, stats);
  }
  if (!grid_problem.empty()) detail::mark_failed(stats, grid_problem);  // never a success with no steps
  const BasicEventFunctions<S>* events = cfg.events;
  if constexpr (detail::has_observable_state<Scheme, Model>) {
    if (events && stats.ok) {  // between outputs the loop never holds the trajectory's state
      detail::mark_failed(stats, "events are not located by a processed composition: use a composition "
                                 "without processing (BASE@kahan-li8)");
      first = n;
    }
  }
  std::vector<double> g;
  detail::FormedObservable<S> formed;   // for a scheme with an observable state
  std::optional<Scheme> scheme_before;  // with events: the scheme as it was before the step
  S x_before;
  if (events) detail::event_values(*events, t, s, g);
  for (std::int64_t k = first; k < n; ++k) {
    const double t_next = k + 1 == n ? cfg.t_end : cfg.t0 + direction * static_cast<double>(k + 1) * cfg.dt;
    if (events) {
      scheme_before.emplace(scheme);
      x_before = s;
    }
    // Initialised in place (no copy: a 32-byte status copied through the stack
    // stalled store forwarding, ~8 ns a step for dmv-pre10).
    const StepStatus st = cfg.retry_halving > 0
                              ? detail::step_with_halving(scheme, model, s, t, t_next - t, cfg.retry_halving, stats.work)
                              : detail::recorded_step(scheme, model, s, t, t_next - t, stats.work);
    if (st.refused) {
      detail::mark_failed(stats, detail::refusal_message(scheme, k + 1, t_next));
      break;
    }
    stats.steps = k + 1;
    if (!st.converged) {
      detail::mark_failed(stats, detail::failure_message(st.reason ? st.reason : "implicit solve did not converge",
                                                         k + 1, t_next, &st));
      if (cfg.retry_halving > 0) stats.status += " after " + std::to_string(cfg.retry_halving) + " halvings of the step";
      break;
    }
    if (!detail::finite_state(s)) {
      detail::mark_failed(stats, detail::failure_message("state became non-finite (blow-up)", k + 1, t_next, nullptr));
      break;
    }
    const double t_start = t;
    t = t_next;
    if (events) {
      std::string why = detail::fixed_step_crossings(scheme, *scheme_before, model, cfg, g, t_start, t, x_before, s,
                                                     k + 1, observer, stats.work);
      if (!why.empty()) {
        detail::mark_failed(stats, std::move(why));
        break;
      }
    }
    if (detail::observe_step(scheme, model, cfg, out, k + 1, t_start, t, k + 1 == n, s, observer, stats, &formed))
      break;
    if (k + 1 < n) detail::offer_checkpoint<Scheme, Model, false>(scheme, cfg, k + 1, t, 0.0, s, stats);
  }
  if constexpr (detail::keeps_attitude<Scheme, Model>) scheme.write_attitude(s);
  // The run's final state is the trajectory's (processed_composition.hpp):
  // the one observed after the last step taken, if it was observed.
  if constexpr (detail::has_observable_state<Scheme, Model>)
    s = formed.step >= 0 && formed.step == stats.steps ? formed.x : scheme.observable(model, s, stats.work);
  stats.t_final = t;
  stats.cpu_seconds = cfg.cpu_clock ? detail::cpu_now() - cpu0 : 0.0;
  return stats;
}

/// Adaptive run: accepted steps advance, rejected ones retry with the
/// proposed smaller step. The run stops (status not ok) if the step falls
/// below 1e-14·max(1, |t|): the error target cannot be met in double
/// precision, or after RunConfig::max_consecutive_rejections rejections in a
/// row. A scheme with dense output (interpolate()) is not shortened to land
/// on output times: they are interpolated inside its steps.
template <class Scheme, class Model, class S>
RunStats integrate_adaptive(Scheme& scheme, const Model& model, S& s, const BasicRunConfig<S>& cfg,
                            BasicObserver<S>& observer) {
  constexpr bool dense = detail::has_dense_output<Scheme, Model>;
  RunStats stats;
  const double cpu0 = cfg.cpu_clock ? detail::cpu_now() : 0.0;
  const StepStatus started = detail::start(scheme, model, s, cfg.t0);
  const std::vector<double>* times = cfg.output_times;
  const double span = cfg.t_end - cfg.t0;
  detail::OutputCursor out{.times = times, .direction = 1.0, .span = span};
  double t = cfg.t0;
  double h = 0.0;
  std::int64_t k = 0, rejected_in_a_row = 0;
  if (const BasicLoopCheckpoint<S>* from = detail::resume_point(cfg); from && !started.refused) {
    if (detail::resume<Scheme, Model, true>(scheme, *from, s, stats)) t = from->t, h = from->h, k = from->step;
    detail::skip_output_times(out, t);
  } else {
    detail::observe_start(scheme, started, cfg.t0, out, s, observer, stats);
    if (stats.ok && span > 0.0) h = cfg.dt > 0.0 ? std::min(cfg.dt, span) : scheme.initial_step(model, s, t, span);
  }
  const BasicEventFunctions<S>* events = cfg.events;
  std::vector<double> g;
  std::optional<Scheme> scheme_before;  // with events on the step map: the scheme as it was before the attempt
  bool on_interpolant = false;           // with events: located on the dense output
  if constexpr (dense) on_interpolant = cfg.event_location == EventLocation::dense_output;
  if (events) detail::event_values(*events, t, s, g);
  while (stats.ok && span > 0.0 && t < cfg.t_end) {
    // The time this step may not pass: t_end, or the next output time before it.
    double target = cfg.t_end;
    double land = 1e-12 * std::abs(cfg.t_end);
    if (!dense && times && out.next < times->size() && (*times)[out.next] < cfg.t_end) {
      target = (*times)[out.next];
      land = detail::land_tolerance(target, span);
    }
    const bool last = t + h >= target || (target - (t + h)) < land;
    const double h_try = last ? target - t : h;
    const S before = s;
    if (events && !on_interpolant) scheme_before.emplace(scheme);
    const AdaptiveStatus a = scheme.attempt(model, s, t, h_try, stats.work);
    detail::record_solve(a.solve, stats.work);
    if (a.solve.refused) {
      detail::mark_failed(stats, detail::refusal_message(scheme, k + (a.accepted ? 1 : 0), t));
      break;
    }
    if (!a.accepted) {
      s = before;
      h = a.h_next;
      ++rejected_in_a_row;
      if (!(h >= 1e-14 * std::max(1.0, std::abs(t))))
        detail::mark_failed(stats, detail::failure_message("adaptive step size collapsed below 1e-14", k, t, nullptr));
      else if (rejected_in_a_row > cfg.max_consecutive_rejections)
        detail::mark_failed(stats, detail::failure_message("too many consecutive rejected steps", k, t, nullptr));
      continue;
    }
    rejected_in_a_row = 0;
    ++k;
    const double t_start = t;
    t = last ? target : t + h_try;
    stats.steps = k;
    if (!detail::finite_state(s)) {
      detail::mark_failed(stats, detail::failure_message("state became non-finite (blow-up)", k, t, nullptr));
      break;
    }
    if (events) {
      // On the dense output, an iteration evaluates the step's interpolant
      // (its extra stages once per step). On the step map, the search takes
      // steps of the pair's propagated solution whatever its error estimate
      // says (a step no longer than an accepted one): step(), the forced
      // attempt. A scheme without step() can only offer its accepted
      // attempts, so a rejected trial there ends the search.
      auto advance = [&](double theta, S& x) {
        if constexpr (dense) {
          if (on_interpolant) {
            scheme.interpolate(model, t_start + theta, x);
            return detail::finite_state(x);
          }
        }
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
        detail::mark_failed(stats, std::move(why));
        break;
      }
    }
    if (detail::observe_step(scheme, model, cfg, out, k, t_start, t, t >= cfg.t_end, s, observer, stats)) break;
    // A step shortened to land on an output time (or t_end, which ends the
    // run) does not shrink the next proposal.
    h = last ? std::max(a.h_next, h) : a.h_next;
    if (t < cfg.t_end) detail::offer_checkpoint<Scheme, Model, true>(scheme, cfg, k, t, h, s, stats);
  }
  stats.t_final = t;
  stats.cpu_seconds = cfg.cpu_clock ? detail::cpu_now() - cpu0 : 0.0;
  return stats;
}

}  // namespace lgi::integrators
