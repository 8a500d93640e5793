#pragma once
// The tangent (variational) flow of the Euler–Poisson field on SO(3) × ℝ³,
// and the chaos indicators built on it: the maximal Lyapunov exponent and
// MEGNO (docs/atlas.md §7).
//
// Tangent vector. v = (ξ, δΠ) ∈ ℝ⁶ perturbs the state (R, Π) to
// (R exp(ξ̂), Π + δΠ): the body-side trivialisation the schemes and the model
// Jacobians use (docs/conventions.md §3, terms/torque_term.hpp). Linearising
// Ṙ = R Ω̂ gives ξ̇ = ξ × Ω + J⁻¹δΠ, and linearising Π̇ = K(R, Π, t) = Π × Ω + τ
// gives δΠ̇ = (∂K/∂η) ξ + (∂K/∂Π) δΠ, the model's momentum_rate_jacobian
// (RigidBody, integrators/system/rigid_body.hpp). So
//   v̇ = A(x(t)) v,  A = [[−Ω̂, J⁻¹], [∂τ/∂η, Π̂J⁻¹ − Ω̂ + ∂τ/∂Π]].
//
// Integration. One step integrates the product (x, v) with RKMK4 (H. Munthe-
// Kaas, "High order Runge–Kutta methods on manifolds", Appl. Numer. Math. 29
// (1999) 115–127; docs/math.md) on the group SO(3) × ℝ³ × ℝ⁶, body
// trivialisation, classical RK4 coefficients: with Θ₁ = 0 and, for the stages
// i = 2, 3, 4, Θᵢ = h aᵢ Fᵢ₋₁, Yᵢ = (R exp(Θᵢ), Π + h aᵢ Kᵢ₋₁),
// Vᵢ = v + h aᵢ Wᵢ₋₁ (a = ½, ½, 1),
//   Fᵢ = dexp⁻¹_Θᵢ Ω(Yᵢ),  Kᵢ = K(Yᵢ, t + cᵢh),  Wᵢ = A(Yᵢ, t + cᵢh) Vᵢ,
// and R' = R exp(h/6 (F₁ + 2F₂ + 2F₃ + F₄)), likewise Π' and v'. On the ℝ⁹
// factor dexp⁻¹ is the identity, so v is advanced by classical RK4 along the
// stage states: the pair is fourth order. Steps of size h are the same as the
// main trajectory's (fixed dt), but this is a separate integration: the main
// run, its steps and its crossings do not depend on whether indicators are
// asked for.
//
// For the models with an ensemble kernel (all but the spring) the indicators
// step with integrators/ensemble/tangent_kernel.hpp's form of this step: the
// same scheme with A applied as directional derivatives (other roundings),
// whose SIMD lanes give the same bits (docs/ensemble.md).
//
// Indicators, with v renormalised to |v| = 1 after every step (Euclidean norm
// on ℝ⁶ in the scene's units) and Δₙ = ln|vₙ| the growth of step n, s the
// time since the start:
//   Lyapunov (G. Benettin, L. Galgani, A. Giorgilli, J.-M. Strelcyn,
//   Meccanica 15 (1980) 9–20, renormalised tangent vector):
//     λ(s) = (1/s) Σ Δₙ;
//   and the same over the run's second half, [T/2, T] (to the step at or
//   after T/2), as an estimate of its convergence;
//   MEGNO (P. M. Cincotta, C. Simó, Astron. Astrophys. Suppl. Ser. 147 (2000)
//   205–228): Y(s) = (2/s) ∫₀ˢ σ (d/dσ ln|δ(σ)|) dσ and its mean
//   ⟨Y⟩(s) = (1/s) ∫₀ˢ Y(σ) dσ; here ∫ over step n is σ_{n−½} Δₙ (midpoint
//   rule) and the mean is the trapezoidal rule over the steps.
// ⟨Y⟩ → 2 on invariant tori (linear growth of |δ|), → 0 near stable periodic
// orbits, and grows like λs/2 on chaotic orbits.
#include <Eigen/Core>
#include <atomic>
#include <cmath>
#include <cstdint>

#include "integrators/core/loop_support.hpp"
#include "integrators/system/rigid_body.hpp"
#include "lie/so3.hpp"

namespace lgi::integrators {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;  // six tangent vectors as columns (the Lyapunov spectrum)

/// A v for one tangent vector v = (ξ, δΠ), given Ω and the model's Jacobian at the state.
template <class Model, class Jacobian>
Vec6 apply_tangent_matrix(const Model& model, const lie::Vec3& Omega, const Jacobian& jac, const Vec6& v) {
  const lie::Vec3 xi = v.head<3>(), dPi = v.tail<3>();
  Vec6 r;
  r.head<3>() = xi.cross(Omega) + model.omega_jacobian() * dPi;
  r.tail<3>() = jac.attitude * xi + jac.momentum * dPi;
  return r;
}

/// v̇ = A(x) v at the state (R, Π) and time t (top of this file).
template <class Model>
Vec6 tangent_rate(const Model& model, const lie::Mat3& R, const lie::Vec3& Pi, double t, const Vec6& v) {
  const lie::Vec3 Omega = model.omega(Pi);
  return apply_tangent_matrix(model, Omega, model.momentum_rate_jacobian(R, Pi, Omega, t), v);
}

/// V̇ = A(x) V for six tangent vectors, the columns of V.
template <class Model>
Mat6 tangent_rate(const Model& model, const lie::Mat3& R, const lie::Vec3& Pi, double t, const Mat6& V) {
  const lie::Vec3 Omega = model.omega(Pi);
  const auto jac = model.momentum_rate_jacobian(R, Pi, Omega, t);
  Mat6 r;
  for (int k = 0; k < 6; ++k) r.col(k) = apply_tangent_matrix(model, Omega, jac, Vec6(V.col(k)));
  return r;
}

/// One RKMK4 step of the product (x, v) of size h from time t (top of this
/// file); v is one tangent vector (Vec6) or six (Mat6), advanced alike.
template <class Model, class Tangent>
void tangent_step(const Model& model, system::State& x, Tangent& v, double t, double h) {
  constexpr double a[4] = {0.0, 0.5, 0.5, 1.0};
  constexpr double b[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
  lie::Vec3 F = lie::Vec3::Zero(), K = lie::Vec3::Zero(), theta = lie::Vec3::Zero(), dPi = lie::Vec3::Zero();
  Tangent W = Tangent::Zero(), dv = Tangent::Zero();
  for (int i = 0; i < 4; ++i) {
    const lie::Vec3 Ti = (h * a[i]) * F;
    const lie::Mat3 Ri = i == 0 ? x.R : lie::Mat3(x.R * lie::exp_so3(Ti));
    const lie::Vec3 Pi_i = x.Pi + (h * a[i]) * K;
    const Tangent Vi = v + (h * a[i]) * W;
    const double ti = t + a[i] * h;
    const lie::Vec3 Omega = model.omega(Pi_i);
    F = i == 0 ? Omega : lie::dexpinv_body(Ti, Omega);
    K = model.momentum_rate(Ri, Pi_i, Omega, ti);
    W = tangent_rate(model, Ri, Pi_i, ti, Vi);
    theta += (h * b[i]) * F;
    dPi += (h * b[i]) * K;
    dv += (h * b[i]) * W;
  }
  x.R = x.R * lie::exp_so3(theta);
  x.Pi += dPi;
  v += dv;
}

/// The running sums of the indicators (top of this file).
class ChaosAccumulator {
 public:
  /// After a step from s − h to s (times since the start) in which |v| grew
  /// from 1 to `growth`.
  void add(double s, double h, double growth) {
    const double d = std::log(growth);
    log_sum_ += d;
    weighted_ += (s - 0.5 * h) * d;
    const double y = 2.0 * weighted_ / s;
    mean_sum_ += 0.5 * h * (y_ + y);
    y_ = y;
    s_ = s;
  }
  /// Remembers the sums so far: lyapunov_since_mark() is λ over the time since.
  void mark() {
    marked_log_sum_ = log_sum_;
    marked_s_ = s_;
  }
  double lyapunov_since_mark() const {
    return s_ > marked_s_ ? (log_sum_ - marked_log_sum_) / (s_ - marked_s_) : std::nan("");
  }
  double lyapunov() const { return s_ > 0.0 ? log_sum_ / s_ : 0.0; }
  double megno() const { return y_; }  // Y(s)
  double mean_megno() const { return s_ > 0.0 ? mean_sum_ / s_ : 0.0; }  // ⟨Y⟩(s)

 private:
  double log_sum_ = 0.0, weighted_ = 0.0, mean_sum_ = 0.0, y_ = 0.0, s_ = 0.0;
  double marked_log_sum_ = 0.0, marked_s_ = 0.0;
};

struct ChaosIndicators {
  double lyapunov = 0.0;   // λ(t_end)
  double megno = 0.0;      // ⟨Y⟩(t_end)
  double megno_y = 0.0;    // Y(t_end)
  double lyapunov_last_half = 0.0;  // λ over [s½, t_end], s½ the first step's end at or after the midpoint
  std::int64_t steps = 0;
  bool ok = true;          // false: the tangent or the state blew up, or `stop` (the values are NaN)
  bool stopped = false;    // `stop` was set: the loop ended early (a signal, the caller's flag)
};

/// The indicators' loop for any state: from t0 to t_end with steps dt (the
/// last one shortened to land on t_end), `step(t, h, v)` advancing the state
/// and the tangent v, `state_finite()` saying whether the state is still
/// finite; v is renormalised after every step (top of this file). A set `stop` flag
/// (read every 256 steps, so well within a second) ends the loop with NaN values.
template <class Step, class StateFinite, class Tangent>
ChaosIndicators accumulate_chaos_indicators(Step&& step, StateFinite&& state_finite, Tangent& v, double t0,
                                            double t_end, double dt, const std::atomic<bool>* stop = nullptr) {
  ChaosIndicators out;
  ChaosAccumulator acc;
  if (!fixed_step_grid_problem(t0, t_end, dt).empty()) {  // t + dt == t would never end the loop
    out.ok = false;
    out.lyapunov = out.megno = out.megno_y = std::nan("");
    return out;
  }
  v.normalize();
  double t = t0;
  bool marked = false;
  while (t < t_end) {
    const double h = (t_end - t) < 1.0000001 * dt ? t_end - t : dt;
    step(t, h, v);
    t = (t_end - t) < 1.0000001 * dt ? t_end : t + h;
    const double n = v.norm();
    if (!std::isfinite(n) || !(n > 0.0) || !state_finite()) {
      out.ok = false;
      out.lyapunov = out.megno = out.megno_y = out.lyapunov_last_half = std::nan("");
      return out;
    }
    v /= n;
    acc.add(t - t0, h, n);
    ++out.steps;
    if (stop != nullptr && out.steps % 256 == 0 && stop->load(std::memory_order_relaxed)) {
      out.ok = false;
      out.stopped = true;
      out.lyapunov = out.megno = out.megno_y = out.lyapunov_last_half = std::nan("");
      return out;
    }
    if (!marked && t - t0 >= 0.5 * (t_end - t0)) {
      acc.mark();
      marked = true;
    }
  }
  out.lyapunov = acc.lyapunov();
  out.lyapunov_last_half = acc.lyapunov_since_mark();
  out.megno = acc.mean_megno();
  out.megno_y = acc.megno();
  return out;
}

/// Integrates (x, v) from t0 to t_end with steps dt and returns the
/// indicators; x and v end at t_end.
template <class Model>
ChaosIndicators chaos_indicators(const Model& model, system::State& x, Vec6 v, double t0, double t_end, double dt,
                                 const std::atomic<bool>* stop = nullptr) {
  return accumulate_chaos_indicators([&](double t, double h, Vec6& w) { tangent_step(model, x, w, t, h); },
                                     [&] { return x.Pi.allFinite(); }, v, t0, t_end, dt, stop);
}

}  // namespace lgi::integrators
