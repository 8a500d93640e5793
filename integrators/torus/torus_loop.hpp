#pragma once
// The time loop for states on T³ × ℝ³ (the Cardan top, docs/cardan.md §5).
//
// It is integrators/stepper_loop.hpp's loop with the state type
// system::TorusState: the same RunConfig, RunStats, StepStatus, WorkCounters,
// the same fixed grid (fixed_step_count; step k covers [t0 + k dt,
// t0 + (k+1) dt], the last clipped to t_end, backward when t_end < t0), the
// same adaptive control (a step collapsing below 1e-14 max(1, |t|), too many
// rejections in a row), the same save_every rule (initial and final states
// always) and the same stop flag. What stepper_loop.hpp has and this loop has
// not: output times, events, checkpoints and dense output; a RunConfig that
// asks for one fails the run with a status saying so. The loop stays
// separate because stepper_loop.hpp, its Observer, EventFunctions and
// LoopCheckpoint are typed on the SO(3) state (docs/cardan.md §7 says what a
// merge would take).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "integrators/loop_support.hpp"
#include "integrators/run_config.hpp"
#include "integrators/system/cardan.hpp"

namespace lgi::integrators::torus {

/// Receives the samples of a run on T³ × ℝ³.
class TorusObserver {
 public:
  virtual ~TorusObserver() = default;
  virtual void observe(std::int64_t step, double t, const system::TorusState& s) = 0;
};

namespace detail {
inline bool finite(const system::TorusState& s) { return s.q.allFinite() && s.p.allFinite(); }
/// Empty if the loop can honour cfg, else why not.
inline std::string unsupported_config(const RunConfig& cfg) {
  if (cfg.output_times) return "output times are not supported on T^3 states";
  if (cfg.events) return "events are not supported on T^3 states";
  if (cfg.checkpoints) return "checkpoints are not supported on T^3 states";
  return {};
}
inline bool stop_now(const RunConfig& cfg) { return cfg.stop && cfg.stop->load(std::memory_order_relaxed); }
}  // namespace detail

template <class Scheme>
RunStats integrate_torus_fixed(Scheme& scheme, const system::CardanTop& model, system::TorusState& s,
                               const RunConfig& cfg, TorusObserver& observer) {
  RunStats stats;
  if (std::string why = detail::unsupported_config(cfg); !why.empty()) {
    integrators::detail::mark_failed(stats, std::move(why));
    return stats;
  }
  if (std::string why = fixed_step_grid_problem(cfg.t0, cfg.t_end, cfg.dt); !why.empty()) {
    integrators::detail::mark_failed(stats, std::move(why));  // never a success with no steps
    return stats;
  }
  const double cpu0 = cfg.cpu_clock ? integrators::detail::cpu_now() : 0.0;
  const double direction = cfg.t_end < cfg.t0 ? -1.0 : 1.0;
  const std::int64_t n = fixed_step_count(direction * (cfg.t_end - cfg.t0), cfg.dt);
  observer.observe(0, cfg.t0, s);
  double t = cfg.t0;
  for (std::int64_t k = 0; k < n; ++k) {
    const double t_next = k + 1 == n ? cfg.t_end : cfg.t0 + direction * static_cast<double>(k + 1) * cfg.dt;
    const StepStatus st = scheme.step(model, s, t, t_next - t, stats.work);
    integrators::detail::record_solve(st, stats.work);
    stats.steps = k + 1;
    if (!st.converged) {
      integrators::detail::mark_failed(
          stats, integrators::detail::failure_message("implicit solve did not converge", k + 1, t_next, &st));
      break;
    }
    if (!detail::finite(s)) {
      integrators::detail::mark_failed(
          stats, integrators::detail::failure_message("state became non-finite (blow-up)", k + 1, t_next, nullptr));
      break;
    }
    t = t_next;
    const bool last = k + 1 == n;
    const bool stopping = !last && detail::stop_now(cfg);
    if ((k + 1) % cfg.save_every == 0 || last || stopping) observer.observe(k + 1, t, s);
    if (stopping) {
      stats.ok = false;
      stats.interrupted = true;
      stats.status = integrators::detail::failure_message(interrupted_status, k + 1, t, nullptr);
      break;
    }
  }
  stats.t_final = t;
  stats.cpu_seconds = cfg.cpu_clock ? integrators::detail::cpu_now() - cpu0 : 0.0;
  return stats;
}

template <class Scheme>
RunStats integrate_torus_adaptive(Scheme& scheme, const system::CardanTop& model, system::TorusState& s,
                                  const RunConfig& cfg, TorusObserver& observer) {
  RunStats stats;
  if (std::string why = detail::unsupported_config(cfg); !why.empty()) {
    integrators::detail::mark_failed(stats, std::move(why));
    return stats;
  }
  const double cpu0 = cfg.cpu_clock ? integrators::detail::cpu_now() : 0.0;
  const double span = cfg.t_end - cfg.t0;
  observer.observe(0, cfg.t0, s);
  double t = cfg.t0;
  double h = span > 0.0 ? (cfg.dt > 0.0 ? std::min(cfg.dt, span) : scheme.initial_step(model, s, t, span)) : 0.0;
  std::int64_t k = 0, rejected_in_a_row = 0;
  while (stats.ok && span > 0.0 && t < cfg.t_end) {
    const double land = 1e-12 * std::abs(cfg.t_end);
    const bool last = t + h >= cfg.t_end || (cfg.t_end - (t + h)) < land;
    const double h_try = last ? cfg.t_end - t : h;
    const system::TorusState before = s;
    const AdaptiveStatus a = scheme.attempt(model, s, t, h_try, stats.work);
    integrators::detail::record_solve(a.solve, stats.work);
    if (!a.accepted) {
      s = before;
      h = a.h_next;
      ++rejected_in_a_row;
      if (!(h >= 1e-14 * std::max(1.0, std::abs(t))))
        integrators::detail::mark_failed(stats, integrators::detail::failure_message(
                                                    "adaptive step size collapsed below 1e-14", k, t, nullptr));
      else if (rejected_in_a_row > cfg.max_consecutive_rejections)
        integrators::detail::mark_failed(
            stats, integrators::detail::failure_message("too many consecutive rejected steps", k, t, nullptr));
      continue;
    }
    rejected_in_a_row = 0;
    ++k;
    t = last ? cfg.t_end : t + h_try;
    stats.steps = k;
    if (!detail::finite(s)) {
      integrators::detail::mark_failed(
          stats, integrators::detail::failure_message("state became non-finite (blow-up)", k, t, nullptr));
      break;
    }
    const bool stopping = t < cfg.t_end && detail::stop_now(cfg);
    if (k % cfg.save_every == 0 || t >= cfg.t_end || stopping) observer.observe(k, t, s);
    if (stopping) {
      stats.ok = false;
      stats.interrupted = true;
      stats.status = integrators::detail::failure_message(interrupted_status, k, t, nullptr);
      break;
    }
    h = last ? std::max(a.h_next, h) : a.h_next;
  }
  stats.t_final = t;
  stats.cpu_seconds = cfg.cpu_clock ? integrators::detail::cpu_now() - cpu0 : 0.0;
  return stats;
}

}  // namespace lgi::integrators::torus
