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
// integrate_fixed on that trajectory alone.
//
// For explicit fixed-step schemes only (a step always succeeds and is never
// refused; retry_halving has nothing to retry). No checkpoints are offered.
// With cpu_clock, the ensemble's CPU time is shared equally by its lanes.
#include <cstdint>
#include <span>
#include <vector>

#include "integrators/ensemble/ensemble.hpp"
#include "integrators/loop_support.hpp"

namespace lgi::integrators::ensemble {

/// What the loop keeps per lane between steps; reused from run to run, so a
/// run allocates nothing once the event-value buffers have their size.
struct EnsembleWorkspace {
  std::vector<double> g[max_lanes];  // event values at the lane's last state
  State before[max_lanes];           // with events: the lane's state before the step
  detail::OutputCursor out[max_lanes];
  bool running[max_lanes] = {};
};

/// Runs states.size() ≤ e.lanes() trajectories, each from its states[l] to
/// cfg.t_end, observed by *observers[l]; stats[l] gets its RunStats and
/// states[l] its final state. Scheme is the scalar scheme e steps as.
template <class Scheme, class Model>
void integrate_fixed_ensemble(EnsembleStepper& e, const Model& model, std::span<State> states, const RunConfig& cfg,
                              std::span<Observer* const> observers, std::span<RunStats> stats, EnsembleWorkspace& ws) {
  static_assert(!requires(Scheme& s, const Model& m, const State& x) { s.start(m, x, 0.0); },
                "integrate_fixed_ensemble runs schemes without start()");
  const int lanes = static_cast<int>(states.size());
  if (lanes == 0) return;
  const Scheme scheme{};  // stateless: event location copies it, observe_step reads its hooks
  const double cpu0 = cfg.cpu_clock ? detail::cpu_now() : 0.0;
  const double direction = cfg.t_end < cfg.t0 ? -1.0 : 1.0;
  const std::int64_t n = fixed_step_count(direction * (cfg.t_end - cfg.t0), cfg.dt);
  const EventFunctions* events = cfg.events;
  for (int l = 0; l < e.lanes(); ++l) e.set_lane(l, states[static_cast<std::size_t>(l < lanes ? l : 0)]);
  for (int l = 0; l < lanes; ++l) {
    const auto u = static_cast<std::size_t>(l);
    stats[u] = RunStats{};
    ws.out[l] = {.times = cfg.output_times, .direction = direction, .span = cfg.t_end - cfg.t0};
    detail::observe_start(scheme, StepStatus{}, cfg.t0, ws.out[l], states[u], *observers[u], stats[u]);
    if (events) detail::event_values(*events, cfg.t0, states[u], ws.g[l]);
    ws.running[l] = true;
  }
  int running = lanes;
  double t = cfg.t0;
  for (std::int64_t k = 0; k < n && running > 0; ++k) {
    const double t_next = k + 1 == n ? cfg.t_end : cfg.t0 + direction * static_cast<double>(k + 1) * cfg.dt;
    const double t_start = t;
    e.step(t_start, t_next - t_start);
    // Whether observe_step may observe at this step (for every lane alike);
    // if not, and without events, a lane's state stays in the block.
    const bool final_step = k + 1 == n;
    const bool may_observe =
        cfg.output_times || (k + 1) % cfg.save_every == 0 || final_step || detail::stop_requested(cfg);
    for (int l = 0; l < lanes; ++l) {
      if (!ws.running[l]) continue;
      const auto u = static_cast<std::size_t>(l);
      RunStats& st = stats[u];
      st.steps = k + 1;
      st.work.rhs_evaluations += e.rhs_per_step();
      if (!e.lane_finite(l)) {
        e.get_lane(l, states[u]);
        detail::mark_failed(st, detail::failure_message("state became non-finite (blow-up)", k + 1, t_next, nullptr));
        st.t_final = t_start;
        ws.running[l] = false, --running;
        continue;
      }
      if (!events && !may_observe) continue;
      if (events) ws.before[l] = states[u];
      e.get_lane(l, states[u]);
      if (events) {
        const State& x0 = ws.before[l];
        auto advance = [&](double theta, State& x) {
          Scheme copy = scheme;
          x = x0;
          return copy.step(model, x, t_start, theta, st.work).converged;
        };
        std::string why = detail::report_crossings(*events, ws.g[l], t_start, t_next - t_start, x0, states[u], k + 1,
                                                   advance, *observers[u]);
        if (!why.empty()) {
          detail::mark_failed(st, std::move(why));
          st.t_final = t_next;
          ws.running[l] = false, --running;
          continue;
        }
      }
      if (detail::observe_step(scheme, model, cfg, ws.out[l], k + 1, t_start, t_next, final_step, states[u],
                               *observers[u], st)) {
        st.t_final = t_next;
        ws.running[l] = false, --running;
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
/// alternative (ensemble_run.cpp).
void run_ensemble(EnsembleStepper& e, const system::AnyModel& model, std::span<State> states, const RunConfig& cfg,
                  std::span<Observer* const> observers, std::span<RunStats> stats, EnsembleWorkspace& ws);

}  // namespace lgi::integrators::ensemble
