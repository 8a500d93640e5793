#pragma once
// Baseline coordinates `rotvec`: rotation vector and body angular velocity,
// x = (Ψ1, Ψ2, Ψ3, Ω1, Ω2, Ω3) ∈ ℝ⁶, R = exp(Ψ̂) (Trindade & Sampaio 2001,
// eq. 8, and eq. 25 for the dynamics).
//
//   Ψ̇ = dexp⁻¹_body(Ψ) Ω = Ω + ½ Ψ × Ω + c(|Ψ|) Ψ × (Ψ × Ω),
//        c(θ) = (1 − (θ/2) cot(θ/2))/θ²                       (docs/math.md §1)
//   Ω̇ = J⁻¹(JΩ × Ω + τ(exp(Ψ̂), JΩ, Ω, t))                   (omega_dynamics.hpp)
// (eq. 25 writes T(Ψ)Ψ̇ = w with T of eq. 10 and the heavy-top torque of
// eq. 21 spelled out; T is dexp_body, so this is the same system.)
//
// Chart switch: the kinematics is singular at |Ψ| = 2π, and |Ψ| grows by the
// spin about Ψ's own axis (a top spinning at 50 rad/s reaches 2π in 0.13 s).
// After every accepted step with |Ψ| > π the scheme (chart_scheme.hpp) replaces Ψ by the
// equivalent Ψ (1 − 2π/|Ψ|) (the same rotation, |Ψ| < π), as any user of the
// rotation vector must; the state changes chart, not attitude (no projection).
//
// Jacobian (rosenbrock4): with u = Ψ × (Ψ × Ω) = Ψ(Ψ·Ω) − Ω|Ψ|²,
//   ∂Ψ̇/∂Ψ = −½ Ω̂ + c ((Ψ·Ω) I + Ψ Ωᵀ − 2 Ω Ψᵀ) + (c′(θ)/θ) u Ψᵀ,
//   ∂Ψ̇/∂Ω = dexp⁻¹_body(Ψ) = I + ½ Ψ̂ + c Ψ̂²,
//   ∂Ω̇/∂Ψ = (∂Ω̇/∂η) dexp_body(Ψ)      (exp(Ψ + dΨ) = exp(Ψ) exp((dexp_body(Ψ) dΨ)^)).
// c′(θ)/θ = 1/360 + θ²/7560 + θ⁴/201600 + θ⁶/5987520 + … (from the series
// c(θ) = Σ_{k≥1} |B_2k|/(2k)! θ^(2k−2) = 1/12 + θ²/720 + θ⁴/30240 + …, since
// x cot x = 1 − Σ 2^{2k} |B_2k| x^{2k}/(2k)!), closed form above θ = 1/2.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <numbers>

#include "integrators/baselines/omega_dynamics.hpp"
#include "lie/charts.hpp"

namespace lgi::integrators::baselines {

/// c′(θ)/θ for c(θ) = (1 − (θ/2)cot(θ/2))/θ² (see above).
inline double dexpinv_coefficient_derivative_over_theta(double theta2) {
  if (theta2 < 0.25) {
    // θ < 1/2: Σ_{k=2..7} (2k−2)|B_2k|/(2k)! θ^(2k−4); the first omitted term,
    // 14 |B_16|/16! θ¹², is below 4e-13 relative. (The closed form loses
    // ~1/(6θ² c′/θ) of its digits to cancellation: 1e-10 relative at θ = 0.1.)
    const double t = theta2;
    return 1.0 / 360.0 +
           t * (1.0 / 7560.0 +
                t * (1.0 / 201600.0 + t * (1.0 / 5987520.0 + t * (691.0 / 130767436800.0 + t / 6227020800.0))));
  }
  const double theta = std::sqrt(theta2);
  const double half = 0.5 * theta;
  const double cot = std::cos(half) / std::sin(half);
  const double sin_half = std::sin(half);
  const double g = half * cot;                                            // (θ/2) cot(θ/2)
  const double g_prime = 0.5 * cot - 0.25 * theta / (sin_half * sin_half);  // dg/dθ
  return -g_prime / (theta2 * theta) - 2.0 * (1.0 - g) / (theta2 * theta2);
}

struct RotationVectorCoordinates {
  static constexpr const char* name = "rotvec";
  static constexpr std::size_t size = 6;
  static constexpr std::size_t omega_offset = 3;
  static constexpr bool euler_angle_chart = false;
  using Vector = std::array<double, size>;
  using Jacobian = Eigen::Matrix<double, 6, 6>;

  /// Ψ = log R (|Ψ| ≤ π), Ω = J⁻¹Π.
  template <class Model>
  static void from_state(const Model& model, const State& s, Vector& x) {
    const Vec3 psi = lie::rotation_vector_from_matrix(s.R);
    const Vec3 W = model.omega(s.Pi);
    x = {psi.x(), psi.y(), psi.z(), W.x(), W.y(), W.z()};
  }
  template <class Model>
  static State to_state(const Model& model, const Vector& x) {
    return {lie::matrix_from_rotation_vector(Vec3(x[0], x[1], x[2])), model.inertia.J * Vec3(x[3], x[4], x[5])};
  }
  /// Distance to the kinematic singularity |Ψ| = 2π.
  static double singularity_margin(const Vector& x) {
    return 2.0 * std::numbers::pi - Vec3(x[0], x[1], x[2]).norm();
  }

  template <class Model>
  static void rhs(const Model& model, const Vector& x, Vector& dxdt, double t) {
    const Vec3 psi(x[0], x[1], x[2]);
    const Vec3 W(x[3], x[4], x[5]);
    const Vec3 psidot = lie::rotation_vector_rate(psi, W);
    Vec3 Wdot;
    if constexpr (Model::has_torque) {
      Wdot = omega_rate(model, lie::matrix_from_rotation_vector(psi), W, t);
    } else {
      Wdot = omega_rate(model, Mat3::Identity(), W, t);
    }
    dxdt = {psidot.x(), psidot.y(), psidot.z(), Wdot.x(), Wdot.y(), Wdot.z()};
  }

  template <class Model>
  static void jacobian(const Model& model, const Vector& x, Jacobian& J, Vector& dfdt, double t) {
    const Vec3 psi(x[0], x[1], x[2]);
    const Vec3 W(x[3], x[4], x[5]);
    const double theta2 = psi.squaredNorm();
    const double c = lie::detail::dexpinv_coefficient(theta2);
    const Vec3 u = psi.cross(psi.cross(W));
    const Mat3 d_psi = -0.5 * lie::hat(W) +
                       c * (psi.dot(W) * Mat3::Identity() + psi * W.transpose() - 2.0 * W * psi.transpose()) +
                       dexpinv_coefficient_derivative_over_theta(theta2) * u * psi.transpose();
    const OmegaRateJacobian dW = omega_rate_jacobian(model, lie::matrix_from_rotation_vector(psi), W, t);
    J.block<3, 3>(0, 0) = d_psi;
    J.block<3, 3>(0, 3) = lie::dexpinv_body_matrix(psi);
    J.block<3, 3>(3, 0) = dW.attitude * lie::dexp_body(psi);
    J.block<3, 3>(3, 3) = dW.omega;
    dfdt = {0.0, 0.0, 0.0, dW.time.x(), dW.time.y(), dW.time.z()};
  }

  /// The chart switch described above. The derivative of the new state is
  /// not the old one: the caller re-evaluates it.
  static bool after_step(Vector& x, Vector* /*dxdt*/, bool& derivative_updated) {
    derivative_updated = false;
    const double n = Vec3(x[0], x[1], x[2]).norm();
    if (!(n > std::numbers::pi)) return false;
    const double f = 1.0 - 2.0 * std::numbers::pi / n;
    x[0] *= f;
    x[1] *= f;
    x[2] *= f;
    return true;
  }
};

}  // namespace lgi::integrators::baselines
