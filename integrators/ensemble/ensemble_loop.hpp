#pragma once
// The time loop of an ensemble (docs/ensemble.md): integrate_fixed
// (stepper_loop.hpp) run for several trajectories at once, their steps
// taken together by an EnsembleStepper. For each lane it does what
// integrate_fixed does for one trajectory, with the same helpers and in the
// same order: the initial sample, after each step the check for a non-finite
// state, the crossings of RunConfig::events (located by the scalar scheme
// from the lane's state before the step, whose steps are bit for bit the
// lane's), the samples due (save_every or output_times) and the stop flag.
// So every lane's RunStats, observe() calls and final state are those of
// integrate_fixed on that trajectory alone. A step that the kernel took in
// every running lane, all finite (EnsembleStepper::step's verdict), with no
// events and no sample due, is only counted lane by lane (10% of a
// dmv-pre10 ensemble's time went to asking each lane what the verdict says).
//
// For an explicit scheme a step always succeeds. For a scheme with memory
// (the preprocessed DMV) each lane's step has the scalar scheme's status
// (EnsembleStepper::outcome), handled as integrate_fixed handles it: the
// work counters, a refusal, a solve that did not converge (after the run's
// halvings), and the scheme's memory before the step for event location.
// No checkpoints are offered. With cpu_clock, the ensemble's CPU time is
// shared equally by its lanes.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "integrators/ensemble/ensemble.hpp"
#include "integrators/core/loop_support.hpp"

namespace lgi::integrators::ensemble {

/// What the loop keeps per lane between steps; reused from run to run, so a
/// run allocates nothing once the event-value buffers have their size.
struct EnsembleWorkspace {
  std::vector<double> g[max_lanes];  // event values at the lane's last state
  State before[max_lanes];           // with events: the lane's state before the step
  detail::OutputCursor out[max_lanes];
  bool running[max_lanes] = {};
  double memory_before[max_lanes][dmv_rows::memory] = {};  // with memory and events: the lane's before the step
};

namespace lane_loop {
namespace scalar_loop = integrators::detail;
/// Adds one step's counters to a run's, as record_solve and the scheme's step do.
inline void add_work(WorkCounters& run, const WorkCounters& step) {
  run.rhs_evaluations += step.rhs_evaluations;
  run.rejected_steps += step.rejected_steps;
  run.newton_failures += step.newton_failures;
  if (step.newton_iterations_max > run.newton_iterations_max) run.newton_iterations_max = step.newton_iterations_max;
}
/// The kernel's step k + 1 of a lane, as outcome() would count it, without a call.
[[gnu::always_inline]] inline void count_kernel_step(const EnsembleStepper& e, std::int64_t k, RunStats& st) {
  st.steps = k + 1;
  st.work.rhs_evaluations += e.rhs_per_step();
  if (e.has_memory() && st.work.newton_iterations_max < 1) st.work.newton_iterations_max = 1;
}
/// Counts lane l's step k + 1 in st as integrate_fixed does; returns whether
/// the lane's run ends there (a refusal or a solve that did not converge).
/// Inlined: called for every lane and step, and GCC kept it out of line (8% of
/// a dmv-pre10 ensemble run, perf; 14% faster inlined).
template <class Scheme>
[[gnu::always_inline]] inline bool count_lane_step(const EnsembleStepper& e, int l, const Scheme& scheme,
                                                   const RunConfig& cfg, std::int64_t k, double t_next, RunStats& st) {
  if (!e.has_memory() || e.kernel_stepped(l)) {
    count_kernel_step(e, k, st);
    return false;
  }
  const LaneOutcome& o = e.outcome(l);
  add_work(st.work, o.work);
  if (o.status.refused) {
    scalar_loop::mark_failed(st, scalar_loop::refusal_message(scheme, k + 1, t_next));
    return true;
  }
  st.steps = k + 1;
  if (o.status.converged) return false;
  scalar_loop::mark_failed(st, scalar_loop::failure_message(o.status.reason ? o.status.reason : "implicit solve did not converge", k + 1, t_next,
                                  &o.status));
  if (cfg.retry_halving > 0) st.status += " after " + std::to_string(cfg.retry_halving) + " halvings of the step";
  return true;
}
/// Each lane's start as integrate_fixed's (the scheme's start(), the first
/// sample, the event values); padding lanes are made inactive. Returns the
/// number of lanes running.
template <class Scheme>
int start_lanes(EnsembleStepper& e, const Scheme& scheme, const RunConfig& cfg, double direction,
                std::span<State> states, std::span<Observer* const> observers, std::span<RunStats> stats,
                EnsembleWorkspace& ws) {
  const int lanes = static_cast<int>(states.size());
  int running = 0;
  for (int l = 0; l < e.lanes(); ++l) {
    const auto u = static_cast<std::size_t>(l < lanes ? l : 0);
    const StepStatus started = e.start_lane(l, states[u], cfg.t0);
    if (l >= lanes) {  // padding: never stepped by a scalar scheme
      e.set_active(l, false);
      continue;
    }
    stats[u] = RunStats{};
    ws.out[l] = {.times = cfg.output_times, .direction = direction, .span = cfg.t_end - cfg.t0};
    scalar_loop::observe_start(scheme, started, cfg.t0, ws.out[l], states[u], *observers[u], stats[u]);
    if (cfg.events) scalar_loop::event_values(*cfg.events, cfg.t0, states[u], ws.g[l]);
    ws.running[l] = !started.refused;
    if (started.refused) stats[u].t_final = cfg.t0;
    e.set_active(l, ws.running[l]);
    running += ws.running[l] ? 1 : 0;
  }
  return running;
}
}  // namespace lane_loop

/// Runs states.size() ≤ e.lanes() trajectories, each from its states[l] to
/// cfg.t_end, observed by *observers[l]; stats[l] gets its RunStats and
/// states[l] its final state. Scheme is the scalar scheme e steps as.
template <class Scheme, class Model>
void integrate_fixed_ensemble(EnsembleStepper& e, const Model& model, std::span<State> states, const RunConfig& cfg,
                              std::span<Observer* const> observers, std::span<RunStats> stats, EnsembleWorkspace& ws) {
  const int lanes = static_cast<int>(states.size());
  if (lanes == 0) return;
  if (const std::string why = fixed_step_grid_problem(cfg.t0, cfg.t_end, cfg.dt); !why.empty()) {
    for (RunStats& st : stats) detail::mark_failed(st, why);  // never a success with no steps
    return;
  }
  const Scheme scheme{};  // its hooks for observe_step; without memory, event location copies it
  const double cpu0 = cfg.cpu_clock ? detail::cpu_now() : 0.0;
  const double direction = cfg.t_end < cfg.t0 ? -1.0 : 1.0;
  const std::int64_t n = fixed_step_count(direction * (cfg.t_end - cfg.t0), cfg.dt);
  const EventFunctions* events = cfg.events;
  int running = lane_loop::start_lanes(e, scheme, cfg, direction, states, observers, stats, ws);
  double t = cfg.t0;
  for (std::int64_t k = 0; k < n && running > 0; ++k) {
    const double t_next = k + 1 == n ? cfg.t_end : cfg.t0 + direction * static_cast<double>(k + 1) * cfg.dt;
    const double t_start = t;
    if (events && e.has_memory())
      for (int l = 0; l < lanes; ++l)
        if (ws.running[l]) e.save_lane_memory(l, ws.memory_before[l]);
    const bool all_in_kernel = e.step(t_start, t_next - t_start, cfg.retry_halving);
    // Whether observe_step may observe at this step (for every lane alike);
    // if not, and without events, a lane's state stays in the block.
    const bool final_step = k + 1 == n;
    const bool may_observe =
        cfg.output_times || (k + 1) % cfg.save_every == 0 || final_step || detail::stop_requested(cfg);
    if (all_in_kernel && !events && !may_observe) {  // every running lane: the kernel's finite step, nothing due
      for (int l = 0; l < lanes; ++l)
        if (ws.running[l]) lane_loop::count_kernel_step(e, k, stats[static_cast<std::size_t>(l)]);
      t = t_next;
      continue;
    }
    for (int l = 0; l < lanes; ++l) {
      if (!ws.running[l]) continue;
      const auto u = static_cast<std::size_t>(l);
      RunStats& st = stats[u];
      bool failed = lane_loop::count_lane_step(e, l, scheme, cfg, k, t_next, st);
      if (!failed && !e.lane_finite(l)) {
        detail::mark_failed(st, detail::failure_message("state became non-finite (blow-up)", k + 1, t_next, nullptr));
        failed = true;
      }
      if (failed) {
        e.get_lane(l, states[u]);
        st.t_final = t_start;
        ws.running[l] = false, --running;
        e.set_active(l, false);
        continue;
      }
      if (!events && !may_observe) continue;
      if (events) ws.before[l] = states[u];
      e.get_lane(l, states[u]);
      if (events) {
        const State& x0 = ws.before[l];
        auto advance = [&](double theta, State& x) {
          x = x0;
          if (e.has_memory()) return e.step_lane_from(l, ws.memory_before[l], x, t_start, theta, cfg.retry_halving, st.work);
          Scheme copy = scheme;
          return copy.step(model, x, t_start, theta, st.work).converged;
        };
        std::string why = detail::report_crossings(*events, ws.g[l], t_start, t_next - t_start, x0, states[u], k + 1,
                                                   advance, *observers[u]);
        if (!why.empty()) {
          detail::mark_failed(st, std::move(why));
          st.t_final = t_next;
          ws.running[l] = false, --running;
          e.set_active(l, false);
          continue;
        }
      }
      if (detail::observe_step(scheme, model, cfg, ws.out[l], k + 1, t_start, t_next, final_step, states[u],
                               *observers[u], st)) {
        st.t_final = t_next;
        ws.running[l] = false, --running;
        e.set_active(l, false);
      }
    }
    t = t_next;
  }
  const double cpu = cfg.cpu_clock ? (detail::cpu_now() - cpu0) / lanes : 0.0;
  for (int l = 0; l < lanes; ++l) {
    const auto u = static_cast<std::size_t>(l);
    if (ws.running[l]) {
      e.get_lane(l, states[u]);
      stats[u].t_final = t;
      ws.running[l] = false;
    }
    stats[u].cpu_seconds = cpu;
  }
}

/// integrate_fixed_ensemble for the scheme e was made for, on the model's
/// alternative (EnsembleStepper::run_lanes, from the scheme's registry entry).
void run_ensemble(EnsembleStepper& e, const system::AnyModel& model, std::span<State> states, const RunConfig& cfg,
                  std::span<Observer* const> observers, std::span<RunStats> stats, EnsembleWorkspace& ws);

}  // namespace lgi::integrators::ensemble
