#pragma once
// A baseline as a scheme of the one time loop (integrators/core/stepper_loop.hpp):
// a chart (euler_zxz.hpp, rotation_vector.hpp, quaternion.hpp, matrix.hpp)
// and an odeint stepper (odeint_steppers.hpp) behind the interface every
// Lie-group scheme offers (scheme_interface.hpp). The chart state x lives in
// the scheme, set from (R, Π) by start() and integrated as it is (Euler
// angles are never wrapped); after each step the loop's State is (R, Π) of x.
// So integrate_fixed / integrate_adaptive own the time grid, output times,
// the stop flag and the statistics for the baselines as for every scheme.
//
// What the chart adds to the loop:
//   - Fixed steps: rk4 on t0 + k dt, the last clipped to t_end. Controlled
//     steppers start from --dt if given, else from Hairer's starting-step
//     algorithm (HNW I §II.4, 2 extra evaluations, counted at the first attempt).
//   - dopri5 has dense output (Shampine 1986, odeint's calc_state): output
//     times inside a step are interpolated, not landed on (interpolate()).
//   - Charts that project after a step (quat-normalized to |q| = 1, rotvec
//     back into |v| ≤ π) do so here, after the step's checks.
//   - The Euler-angle singularity guard, below, refuses a step
//     (StepStatus::refused): the run stops with the status naming the
//     singularity, t and θ, and the final state is the last accepted one.
//
// The Euler-angle singularity. ψ̇ and φ̇ carry 1/sinθ (Trindade & Sampaio
// 2001, eq. 27), so near θ ∈ {0, π} the chart's rates are unbounded while the
// motion is not, and ψ, φ are separately undefined at θ = 0, π (eq. 14). With
// RunConfig::chart_guards on (the default) a run ends when an accepted step
//   (a) ends with |sinθ| < s_min, or evaluated the chart at a stage with
//       |sinθ| < s_min (s_min = 1e-6: at |sinθ| = 1e-6 an attitude known to
//       1e-6 rad leaves ψ and φ uncertain by ~1 rad, and θ near π is resolved
//       only to ε π / s_min ≈ 5e-10 relative in sinθ),
//   (b) crossed the singular set (sinθ changed sign over the step: the chart
//       was jumped over, not integrated through), or
//   (c) for the fixed-step rk4 only: would turn ψ by more than 0.1 rad in one
//       step at the rate of one of its stages (h |ψ̇| > 0.1). Near the
//       singular set ψ̇ ~ |Ω⊥|/sinθ (1e4 rad/s where heavy_top_trindade_4
//       swings past θ = π at |sinθ| = 5.8e-4). A controlled stepper resolves
//       that with small steps; a fixed step does not, and returns a wrong
//       attitude without any other symptom: euler-zxz/rk4 unguarded on that
//       scene, t = 4 s, is off by 0.036 rad at dt = 1e-3 and 8e-5 rad at
//       dt = 1e-4 (quat/rk4 at 1e-3: 8e-12), and right (6e-10) only at
//       dt = 1e-5, where h |ψ̇| = 0.1. On the regular Trindade cases at the
//       scenes' dt = 1e-3 the spin turns 0.05 rad per step; the bound is
//       twice that (experiments/SINGULARITY.md).
// It also refuses an initial attitude with |sinθ| < s_min, and names the
// singularity when a controlled step collapses with |sinθ| < 1e-2. Rejected
// attempts are not checked: the error estimate rejects them anyway. "ok"
// thus always means a run whose every step kept its accuracy; the study
// (lgi singularity) turns the guards off to show what an unguarded run does.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "integrators/baselines/odeint_steppers.hpp"
#include "integrators/core/stepper_loop.hpp"

namespace lgi::integrators::baselines {

inline constexpr double default_euler_singular_threshold = 1e-6;
inline constexpr double default_euler_fixed_step_resolution = 0.1;

namespace detail_chart {

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

}  // namespace detail_chart

/// The baseline Coords/StepperT as a scheme of the time loop (top of this file).
template <class Coords, template <class> class StepperT>
class ChartScheme {
 public:
  using Vector = typename Coords::Vector;
  using Stepper = StepperT<Coords>;

  ChartScheme(double tol, bool guarded) : stepper_(tol), tol_(tol), guarded_(guarded) {}

  template <class Model>
  StepStatus start(const Model& model, const State& s, double t0) {
    Coords::from_state(model, s, x_);
    steps_ = 0;
    if constexpr (Coords::euler_angle_chart) {
      if (guarded_ && Coords::singularity_margin(x_) < default_euler_singular_threshold)
        return refuse(detail_chart::euler_singularity_message("the initial attitude is on or next to the singular set",
                                                              0, t0, x_[1], default_euler_singular_threshold));
    }
    (void)t0;
    return {};
  }

  template <class Model>
    requires(!Stepper::adaptive)
  StepStatus step(const Model& model, State& s, double t, double h, WorkCounters& work) {
    const Vector x_prev = x_;
    watch_.reset();
    stepper_.step(system(model, work), x_, t, h);
    if (std::string why = check(x_prev, steps_ + 1, t + h, h); !why.empty()) return refuse_step(model, s, x_prev, why);
    ++steps_;
    bool derivative_updated = false;
    Coords::after_step(x_, nullptr, derivative_updated);
    s = Coords::to_state(model, x_);
    return {};
  }

  template <class Model>
    requires Stepper::adaptive
  double initial_step(const Model& model, const State& /*s*/, double t, double span) {
    const CountingSystem<Coords, Model> sys{&model, &pending_evaluations_, &watch_};
    return detail_chart::initial_step<Coords>(sys, x_, t, span, tol_, Stepper::error_order);
  }

  template <class Model>
    requires Stepper::adaptive
  AdaptiveStatus attempt(const Model& model, State& s, double t, double h, WorkCounters& work) {
    work.rhs_evaluations += pending_evaluations_;  // the starting-step algorithm's
    pending_evaluations_ = 0;
    AdaptiveStatus a;
    const Vector x_prev = x_;
    watch_.reset();
    double h_next = h;
    a.accepted = stepper_.attempt(system(model, work), x_, t, h_next);
    a.h_next = h_next;
    if (!a.accepted) {
      ++work.rejected_steps;
      if constexpr (Coords::euler_angle_chart) {
        if (!(h_next >= 1e-14 * std::max(1.0, std::abs(t))) && std::abs(std::sin(x_[1])) < 1e-2) {
          const std::string m = detail::failure_message("adaptive step size collapsed below 1e-14", steps_, t, nullptr);
          a.solve = refuse(detail_chart::euler_singularity_message(
              "the adaptive step size collapsed below 1e-14 (" + m + ")", steps_, t, x_[1], 0.0));
        }
      }
      return a;
    }
    if (std::string why = check(x_prev, steps_ + 1, t + h, h); !why.empty()) {
      a.solve = refuse_step(model, s, x_prev, why);
      return a;
    }
    ++steps_;
    bool derivative_updated = false;
    if (Coords::after_step(x_, stepper_.derivative(), derivative_updated)) stepper_.state_changed(derivative_updated);
    s = Coords::to_state(model, x_);
    return a;
  }

  /// The state at t inside the last accepted step (dopri5's dense output).
  template <class Model>
    requires Stepper::dense_output
  void interpolate(const Model& model, double t, State& out) {
    stepper_.interpolate(t, x_interpolated_);
    out = Coords::to_state(model, x_interpolated_);
  }

  /// The raw integrated angles (Observer::observe_euler_zxz) at the step's end
  /// and at the last interpolate().
  lie::EulerZXZ euler_angles() const
    requires Coords::euler_angle_chart
  {
    return Coords::angles(x_);
  }
  lie::EulerZXZ interpolated_euler_angles() const
    requires(Coords::euler_angle_chart && Stepper::dense_output)
  {
    return Coords::angles(x_interpolated_);
  }

  /// Why the last refused step was refused (StepStatus::refused).
  const std::string& refusal_reason() const { return refusal_; }

 private:
  template <class Model>
  CountingSystem<Coords, Model> system(const Model& model, WorkCounters& work) {
    return {&model, &work.rhs_evaluations, &watch_};
  }

  StepStatus refuse(std::string why) {
    refusal_ = std::move(why);
    StepStatus st;
    st.refused = true;
    return st;
  }
  /// The run ends at the last accepted state: x and the loop's state go back to it.
  template <class Model>
  StepStatus refuse_step(const Model& model, State& s, const Vector& x_prev, std::string why) {
    x_ = x_prev;
    s = Coords::to_state(model, x_);
    return refuse(std::move(why));
  }

  /// The checks after an accepted step from x_prev to x_; empty if the run goes on.
  std::string check(const Vector& x_prev, std::int64_t k, double t_new, double h) const {
    if (!detail_chart::finite(x_)) {
      std::string m = detail::failure_message("state became non-finite (blow-up)", k, t_new, nullptr);
      if constexpr (Coords::euler_angle_chart)
        m += " (Euler-angle singularity: |sin theta| reached " + detail_chart::format(watch_.min_margin, 3) +
             " at theta = " + detail_chart::format(watch_.theta_at_min) + ")";
      return m;
    }
    if constexpr (Coords::euler_angle_chart) {
      if (guarded_) return euler_guard(x_prev, k, t_new, h);
    }
    (void)x_prev;
    (void)h;
    return {};
  }

  /// (a), (b) and (c) of the top of this file.
  std::string euler_guard(const Vector& x_prev, std::int64_t k, double t_new, double h) const {
    using detail_chart::euler_singularity_message;
    constexpr double s_min = default_euler_singular_threshold;
    if (Coords::singularity_margin(x_) < s_min)
      return euler_singularity_message("the step ended next to the singular set", k, t_new, x_[1], s_min);
    if (watch_.min_margin < s_min)
      return euler_singularity_message("a stage of the step evaluated the chart next to the singular set", k,
                                       watch_.t_at_min, watch_.theta_at_min, s_min);
    if (std::sin(x_prev[1]) * std::sin(x_[1]) < 0.0)
      return euler_singularity_message("the step crossed the singular set (sin theta changed sign)", k, t_new, x_[1],
                                       s_min);
    if constexpr (!Stepper::adaptive) {
      constexpr double r = default_euler_fixed_step_resolution;
      if (!(h * watch_.max_precession_rate <= r))
        return euler_singularity_message("the fixed step cannot resolve the chart (h |psidot| = " +
                                             detail_chart::format(h * watch_.max_precession_rate, 3) + " > " +
                                             detail_chart::format(r, 3) + " rad)",
                                         k, t_new, x_[1], 0.0);
    }
    (void)h;
    return {};
  }

  Stepper stepper_;
  double tol_;
  bool guarded_;
  Vector x_{};
  Vector x_interpolated_{};
  std::int64_t steps_ = 0;
  std::int64_t pending_evaluations_ = 0;
  ChartWatch watch_;
  std::string refusal_;
};

/// One baseline run through the time loop: chart Coords, stepper StepperT<Coords>, any model.
template <class Coords, template <class> class StepperT, class Model>
RunStats run_baseline(const Model& model, State& s, const RunConfig& cfg, Observer& observer) {
  auto refused = [](const char* why) {
    RunStats stats;
    stats.ok = false;
    stats.status = why;
    return stats;
  };
  if (cfg.events)  // SchemeInfo::locates_events is false for the baselines
    return refused("the baselines do not locate events (RunConfig::events); use a Lie-group scheme");
  if (cfg.t_end < cfg.t0) return refused("the baselines integrate forward in time only (t_end < t0)");
  ChartScheme<Coords, StepperT> scheme(cfg.tol, cfg.chart_guards);
  if constexpr (StepperT<Coords>::adaptive) return integrate_adaptive(scheme, model, s, cfg, observer);
  else return integrate_fixed(scheme, model, s, cfg, observer);
}

}  // namespace lgi::integrators::baselines
