#pragma once
// The run loop of the baselines: a chart (euler_zxz.hpp, rotation_vector.hpp,
// quaternion.hpp, matrix.hpp) and an odeint stepper (odeint_steppers.hpp)
// integrated over [t0, t_end] with the contract of integrators/stepper_loop.hpp:
// the initial state, every save_every-th accepted step and the final state go
// to the observer as (R, Π) (Euler-angle charts first report their raw
// angles through Observer::observe_euler_zxz); RunStats carries the accepted
// steps, rejected steps, right-hand-side evaluations, CPU seconds and the
// status; a run that cannot go on stops with ok = false and says why.
// RunConfig::output_times and RunConfig::stop are honoured as there.
//
// Time grid: fixed steps on t0 + k dt, the last clipped to t_end (as
// integrate_fixed); controlled steppers start from --dt if given, else from
// Hairer's starting-step algorithm (HNW I §II.4, 2 extra evaluations), and
// clip the last step to t_end. Stops (status not "ok"):
//   - a non-finite state;
//   - a controlled step below 1e-14 max(1, |t|), or 1000 rejections in a row;
//   - the Euler-angle singularity (euler-zxz only), below.
// After a stop the final state is the last accepted state before the
// offending step; nothing after it was observed.
//
// The Euler-angle singularity. ψ̇ and φ̇ carry 1/sinθ (eq. 27), so near
// θ ∈ {0, π} the chart's rates are unbounded while the motion is not, and ψ,
// φ are separately undefined at θ = 0, π (eq. 14). The runner does not return
// angles it cannot vouch for: the run ends, with a status naming the
// Euler-angle singularity, t and θ, when an accepted step
//   (a) ends with |sinθ| < s_min, or evaluated the chart at a stage with
//       |sinθ| < s_min (s_min = BaselineOptions::euler_singular_threshold,
//       default 1e-6: at |sinθ| = 1e-6 an attitude known to 1e-6 rad leaves ψ
//       and φ uncertain by ~1 rad, and θ near π is resolved only to
//       ε π / s_min ≈ 5e-10 relative in sinθ),
//   (b) crossed the singular set (sinθ changed sign over the step: the chart
//       was jumped over, not integrated through), or
//   (c) for the fixed-step rk4 only: would turn ψ by more than
//       euler_fixed_step_resolution rad in one step at the rate of one of its
//       stages, h |ψ̇| > 0.1 by default. Near the singular set ψ̇ ~ |Ω⊥|/sinθ
//       (1e4 rad/s where heavy_top_trindade_4 swings past θ = π at
//       |sinθ| = 5.8e-4). A controlled stepper resolves that with small steps;
//       a fixed step does not, and returns a wrong attitude without any other
//       symptom: euler-zxz/rk4 unguarded on that scene, t = 4 s, is off by
//       0.036 rad at dt = 1e-3 and 8e-5 rad at dt = 1e-4 (quat/rk4 at 1e-3:
//       8e-12), and right (6e-10) only at dt = 1e-5, where h |ψ̇| = 0.1. On
//       the regular Trindade cases at the scenes' dt = 1e-3 the spin turns
//       0.05 rad per step; the bound is twice that (SINGULARITY.md).
// Rejected attempts are not checked: the error estimate rejects them anyway.
// The rk4 case stops rather than warns, so that "ok" always means a run whose
// every step kept its accuracy; the study (lgi singularity) turns the guard
// off to show what an unguarded run does.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "integrators/baselines/odeint_steppers.hpp"
#include "integrators/stepper_loop.hpp"

namespace lgi::integrators::baselines {

inline constexpr double default_euler_singular_threshold = 1e-6;
inline constexpr double default_euler_fixed_step_resolution = 0.1;

struct BaselineOptions {
  /// s_min of (a); 0 turns (a) and (b) off (an unguarded run, for the study).
  double euler_singular_threshold = default_euler_singular_threshold;
  /// The bound on h |ψ̇| of (c); 0 turns (c) off.
  double euler_fixed_step_resolution = default_euler_fixed_step_resolution;
  /// If set (sorted, within [t0, t_end]): observe exactly at these times and
  /// nowhere else (save_every is ignored). dopri5 interpolates with its dense
  /// output; the other controlled steppers shorten the step to land on each
  /// time (the proposal for the following step is not shortened); rk4 observes
  /// the times that fall on its grid t0 + k dt (others are skipped). Several
  /// samples may then share a step number.
  const std::vector<double>* output_times = nullptr;
  std::int64_t max_consecutive_rejections = 1000;
};

namespace detail_baseline {

inline std::string format(double x, int precision = 17) {
  std::ostringstream s;
  s.precision(precision);
  s << x;
  return s.str();
}

inline std::string euler_singularity_message(const std::string& what, std::int64_t step, double t, double theta,
                                             double threshold) {
  return "Euler-angle singularity: " + what + " at step " + std::to_string(step) + ", t = " + format(t) +
         ", theta = " + format(theta) + " (|sin theta| = " + format(std::abs(std::sin(theta)), 3) +
         (threshold > 0.0 ? ", threshold " + format(threshold, 3) : std::string()) +
         "); psi and phi are undefined at theta = 0 and pi, so the run stops here instead of returning angles it "
         "cannot vouch for";
}

/// Hairer's starting step (HNW I §II.4), in the error measure of error_control.hpp.
template <class Coords, class Sys>
double initial_step(const Sys& sys, const typename Coords::Vector& x0, double t0, double span, double tol,
                    int error_order) {
  typename Coords::Vector f0{}, x1{}, f1{}, d{};
  sys(x0, f0, t0);
  const double w = omega_block_scale<Coords>(x0, f0, 0.0);
  const double d0 = weighted_error<Coords>(x0, w, tol, tol);
  const double d1 = weighted_error<Coords>(f0, w, tol, tol);
  double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  h0 = std::min(h0, span);
  for (std::size_t i = 0; i < Coords::size; ++i) x1[i] = x0[i] + h0 * f0[i];
  sys(x1, f1, t0 + h0);
  for (std::size_t i = 0; i < Coords::size; ++i) d[i] = f1[i] - f0[i];
  const double d2 = weighted_error<Coords>(d, w, tol, tol) / h0;
  const double m = std::max(d1, d2);
  const double h1 = m <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / m, 1.0 / (error_order + 1));
  const double h = std::min({100.0 * h0, h1, span});
  return std::isfinite(h) && h > 0.0 ? h : span;
}

template <class Vector>
bool finite(const Vector& x) {
  for (double v : x)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace detail_baseline

/// One baseline run: chart Coords, stepper StepperT<Coords>, any model.
template <class Coords, template <class> class StepperT, class Model>
RunStats run_baseline(const Model& model, State& s, const RunConfig& cfg, Observer& observer,
                      const BaselineOptions& opt = {}) {
  using Vector = typename Coords::Vector;
  using Stepper = StepperT<Coords>;
  using detail_baseline::euler_singularity_message;
  RunStats stats;
  if (cfg.events) {  // SchemeInfo::locates_events is false for the baselines
    stats.ok = false;
    stats.status = "the baselines do not locate events (RunConfig::events); use a Lie-group scheme";
    return stats;
  }
  const double cpu0 = detail::cpu_now();
  ChartWatch watch;
  const CountingSystem<Coords, Model> sys{&model, &stats.work.rhs_evaluations, &watch};
  Vector x{};
  Coords::from_state(model, s, x);
  double t = cfg.t0;
  const double span = cfg.t_end - cfg.t0;
  const double s_min = opt.euler_singular_threshold;

  // Output times from the run configuration (every scheme's contract,
  // integrators/stepper_loop.hpp) or, for the singularity study, the options.
  const std::vector<double>* grid = opt.output_times ? opt.output_times : cfg.output_times;
  std::int64_t emitted_at = -1;  // the step of the last sample
  std::size_t next = 0;  // next output time
  auto emit = [&](std::int64_t k, double tt, const Vector& xx) {
    if constexpr (Coords::euler_angle_chart) observer.observe_euler_zxz(Coords::angles(xx));
    observer.observe(k, tt, Coords::to_state(model, xx));
    emitted_at = k;
  };
  auto land_tolerance = [&](double tt) { return detail::land_tolerance(tt, span); };
  auto fail = [&](std::string why) {
    stats.ok = false;
    stats.status = std::move(why);
  };
  // RunConfig::stop, read once per accepted step before t_end: the run ends
  // there, its last state observed once (stepper_loop.hpp's rule).
  auto stopped = [&](std::int64_t k, double tt) {
    if (!(tt < cfg.t_end) || !detail::stop_requested(cfg)) return false;
    observer.on_stop();
    if (emitted_at != k) emit(k, tt, x);
    detail::mark_interrupted(stats, k, tt);
    return true;
  };

  // The initial sample.
  if (grid) {
    while (next < grid->size() && (*grid)[next] < t - land_tolerance(t)) ++next;
    if (next < grid->size() && std::abs((*grid)[next] - t) <= land_tolerance(t)) emit(0, (*grid)[next++], x);
  } else {
    emit(0, t, x);
  }

  // Checks after an accepted step from x_prev to x; empty if the run goes on.
  auto check_step = [&](const Vector& x_prev, std::int64_t k, double t_new, double h) -> std::string {
    if (!detail_baseline::finite(x)) {
      std::string m = detail::failure_message("state became non-finite (blow-up)", k, t_new, nullptr);
      if constexpr (Coords::euler_angle_chart)
        m += " (Euler-angle singularity: |sin theta| reached " + detail_baseline::format(watch.min_margin, 3) +
             " at theta = " + detail_baseline::format(watch.theta_at_min) + ")";
      return m;
    }
    if constexpr (Coords::euler_angle_chart) {
      if (s_min > 0.0) {
        if (Coords::singularity_margin(x) < s_min)
          return euler_singularity_message("the step ended next to the singular set", k, t_new, x[1], s_min);
        if (watch.min_margin < s_min)
          return euler_singularity_message("a stage of the step evaluated the chart next to the singular set", k,
                                           watch.t_at_min, watch.theta_at_min, s_min);
        if (std::sin(x_prev[1]) * std::sin(x[1]) < 0.0)
          return euler_singularity_message("the step crossed the singular set (sin theta changed sign)", k, t_new,
                                           x[1], s_min);
      }
      if constexpr (!Stepper::adaptive) {
        const double r = opt.euler_fixed_step_resolution;
        if (r > 0.0 && !(h * watch.max_precession_rate <= r))
          return euler_singularity_message("the fixed step cannot resolve the chart (h |psidot| = " +
                                               detail_baseline::format(h * watch.max_precession_rate, 3) + " > " +
                                               detail_baseline::format(r, 3) + " rad)",
                                           k, t_new, x[1], 0.0);
      }
    }
    (void)x_prev;
    (void)h;
    return {};
  };

  if (span < 0.0) fail("the baselines integrate forward in time only (t_end < t0)");
  if constexpr (Coords::euler_angle_chart) {
    if (stats.ok && s_min > 0.0 && Coords::singularity_margin(x) < s_min)
      fail(euler_singularity_message("the initial attitude is on or next to the singular set", 0, t, x[1], s_min));
  }

  if constexpr (!Stepper::adaptive) {
    Stepper stepper;
    const std::int64_t n = stats.ok ? fixed_step_count(span, cfg.dt) : 0;
    for (std::int64_t k = 0; k < n; ++k) {
      const double t_next = k + 1 == n ? cfg.t_end : cfg.t0 + static_cast<double>(k + 1) * cfg.dt;
      const double h = t_next - t;
      const Vector x_prev = x;
      watch.reset();
      stepper.step(sys, x, t, h);
      if (std::string why = check_step(x_prev, k + 1, t_next, h); !why.empty()) {
        x = x_prev;
        fail(std::move(why));
        break;
      }
      stats.steps = k + 1;
      t = t_next;
      bool derivative_updated = false;
      Coords::after_step(x, nullptr, derivative_updated);
      if (grid) {
        const double tol_t = 1e-9 * cfg.dt;
        while (next < grid->size() && (*grid)[next] < t - tol_t) ++next;
        if (next < grid->size() && std::abs((*grid)[next] - t) <= tol_t) emit(k + 1, (*grid)[next++], x);
      } else if ((k + 1) % cfg.save_every == 0 || k + 1 == n) {
        emit(k + 1, t, x);
      }
      if (stopped(k + 1, t)) break;
    }
  } else {
    Stepper stepper(cfg.tol);
    double h = 0.0;
    if (stats.ok && span > 0.0)
      h = cfg.dt > 0.0 ? std::min(cfg.dt, span)
                       : detail_baseline::initial_step<Coords>(sys, x, t, span, cfg.tol, Stepper::error_order);
    std::int64_t k = 0, consecutive_rejections = 0;
    while (stats.ok && span > 0.0 && t < cfg.t_end) {
      double target = cfg.t_end;
      if constexpr (!Stepper::dense_output) {
        if (grid && next < grid->size() && (*grid)[next] < cfg.t_end) target = (*grid)[next];
      }
      const bool last = t + h >= target || (target - (t + h)) < land_tolerance(target);
      const double h_try = last ? target - t : h;
      double h_next = h_try;
      const Vector x_prev = x;
      watch.reset();
      if (!stepper.attempt(sys, x, t, h_next)) {
        ++stats.work.rejected_steps;
        ++consecutive_rejections;
        h = h_next;
        if (!(h >= 1e-14 * std::max(1.0, std::abs(t)))) {
          std::string m = detail::failure_message("adaptive step size collapsed below 1e-14", k, t, nullptr);
          if constexpr (Coords::euler_angle_chart)
            if (std::abs(std::sin(x[1])) < 1e-2)
              m = euler_singularity_message("the adaptive step size collapsed below 1e-14 (" + m + ")", k, t, x[1],
                                            0.0);
          fail(std::move(m));
        } else if (consecutive_rejections > opt.max_consecutive_rejections) {
          fail(detail::failure_message("too many consecutive rejected steps", k, t, nullptr));
        }
        continue;
      }
      consecutive_rejections = 0;
      const double t_new = last ? target : t + h_try;
      if (std::string why = check_step(x_prev, k + 1, t_new, h_try); !why.empty()) {
        x = x_prev;
        fail(std::move(why));
        break;
      }
      ++k;
      stats.steps = k;
      const double t_old = t;
      t = t_new;
      if constexpr (Stepper::dense_output) {
        // Output times inside the step, from the dense output of the step as taken.
        while (grid && next < grid->size() && (*grid)[next] <= t + land_tolerance(t)) {
          const double to = (*grid)[next++];
          if (std::abs(to - t) <= land_tolerance(t)) {
            emit(k, to, x);
          } else if (to >= t_old) {
            Vector xo{};
            stepper.interpolate(to, xo);
            emit(k, to, xo);
          }
        }
      }
      bool derivative_updated = false;
      if (Coords::after_step(x, stepper.derivative(), derivative_updated)) stepper.state_changed(derivative_updated);
      if (grid) {
        if constexpr (!Stepper::dense_output) {
          if (next < grid->size() && std::abs((*grid)[next] - t) <= land_tolerance(t)) emit(k, (*grid)[next++], x);
        }
      } else if (k % cfg.save_every == 0 || t >= cfg.t_end) {
        emit(k, t, x);
      }
      if (stopped(k, t)) break;
      // A step shortened to land on t_end or an output time does not shrink the next proposal.
      h = last ? std::max(h_next, h) : h_next;
    }
  }
  s = Coords::to_state(model, x);
  stats.t_final = t;
  stats.cpu_seconds = detail::cpu_now() - cpu0;
  return stats;
}

}  // namespace lgi::integrators::baselines
