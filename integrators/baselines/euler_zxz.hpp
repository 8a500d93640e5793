#pragma once
// Baseline coordinates `euler-zxz`: Euler angles ZXZ and the body angular
// velocity, x = (ψ, θ, φ, Ω1, Ω2, Ω3) ∈ ℝ⁶.
//
// Trindade & Sampaio (2001), eq. 26 with the kinematics inverted as in their
// eq. 27 (docs/conventions.md §2):
//   ψ̇ = (Ω1 sinφ + Ω2 cosφ)/sinθ
//   θ̇ =  Ω1 cosφ − Ω2 sinφ
//   φ̇ =  Ω3 − cosθ (Ω1 sinφ + Ω2 cosφ)/sinθ
//   Ω̇ = J⁻¹(JΩ × Ω + τ(R(ψ, θ, φ), JΩ, Ω, t))        (omega_dynamics.hpp)
// with R = Rz(ψ) Rx(θ) Rz(φ) (their eq. 12; Goldstein). The angles are
// integrated as they are: ψ and φ are never wrapped, θ is never reflected.
// The chart is singular where sinθ = 0 (det T = −sinθ, their eq. 16): the
// rates grow like 1/sinθ and ψ, φ are separately undefined at θ ∈ {0, π}.
// What the baselines do there is documented in chart_scheme.hpp.
//
// Jacobian (rosenbrock4), with a = ψ̇, b = θ̇ (∂ of the three rows above):
//   ∂ψ̇/∂θ = −a cosθ/sinθ, ∂ψ̇/∂φ = b/sinθ, ∂ψ̇/∂Ω1 = sinφ/sinθ, ∂ψ̇/∂Ω2 = cosφ/sinθ
//   ∂θ̇/∂φ = −a sinθ,       ∂θ̇/∂Ω1 = cosφ,  ∂θ̇/∂Ω2 = −sinφ
//   ∂φ̇/∂θ =  a/sinθ,       ∂φ̇/∂φ = −b cosθ/sinθ, ∂φ̇/∂Ω1 = −cosθ sinφ/sinθ,
//   ∂φ̇/∂Ω2 = −cosθ cosφ/sinθ, ∂φ̇/∂Ω3 = 1
//   ∂Ω̇/∂(ψ, θ, φ) = (∂Ω̇/∂η) T,  T = [(sinθ sinφ, sinθ cosφ, cosθ), (cosφ, −sinφ, 0), (0, 0, 1)]
// since R(Θ + dΘ) = R(Θ) exp((T dΘ)^) to first order (T of eq. 16, Ω = T Θ̇).
#include <Eigen/Core>
#include <array>
#include <cmath>

#include "integrators/baselines/omega_dynamics.hpp"
#include "lie/charts.hpp"

namespace lgi::integrators::baselines {

struct EulerZxzCoordinates {
  static constexpr const char* name = "euler-zxz";
  static constexpr std::size_t size = 6;
  static constexpr std::size_t omega_offset = 3;
  static constexpr bool euler_angle_chart = true;
  using Vector = std::array<double, size>;
  using Jacobian = Eigen::Matrix<double, 6, 6>;

  /// R = Rz(ψ) Rx(θ) Rz(φ) from the sines and cosines (eq. 12 written out),
  /// so the right-hand side computes each trigonometric function once.
  static Mat3 rotation(double cps, double sps, double cth, double sth, double cph, double sph) {
    Mat3 R;
    R << cps * cph - sps * cth * sph, -cps * sph - sps * cth * cph, sps * sth,  //
        sps * cph + cps * cth * sph, -sps * sph + cps * cth * cph, -cps * sth,  //
        sth * sph, sth * cph, cth;
    return R;
  }

  /// Chart coordinates of a state: the angles by lie::euler_zxz_from_matrix
  /// (θ ∈ [0, π]; at a singular attitude φ = 0 and ψ takes ψ ± φ), Ω = J⁻¹Π.
  template <class Model>
  static void from_state(const Model& model, const State& s, Vector& x) {
    const lie::EulerZXZ e = lie::euler_zxz_from_matrix(s.R).angles;
    const Vec3 W = model.omega(s.Pi);
    x = {e.psi, e.theta, e.phi, W.x(), W.y(), W.z()};
  }

  /// (R, Π) for the observer: R by lie::matrix_from_euler_zxz, Π = JΩ.
  template <class Model>
  static State to_state(const Model& model, const Vector& x) {
    return {lie::matrix_from_euler_zxz({x[0], x[1], x[2]}), model.inertia.J * Vec3(x[3], x[4], x[5])};
  }

  static lie::EulerZXZ angles(const Vector& x) { return {x[0], x[1], x[2]}; }
  /// The chart's distance to its singular set, |sinθ|.
  static double singularity_margin(const Vector& x) { return std::abs(std::sin(x[1])); }
  /// ψ̇ and θ̇ at x (for the observers of the singularity study and the
  /// fixed-step resolution check).
  static double precession_rate(const Vector& x) {
    return (x[3] * std::sin(x[2]) + x[4] * std::cos(x[2])) / std::sin(x[1]);
  }
  static double nutation_rate(const Vector& x) { return x[3] * std::cos(x[2]) - x[4] * std::sin(x[2]); }

  template <class Model>
  static void rhs(const Model& model, const Vector& x, Vector& dxdt, double t) {
    const double sth = std::sin(x[1]), cth = std::cos(x[1]);
    const double sph = std::sin(x[2]), cph = std::cos(x[2]);
    const double a = (x[3] * sph + x[4] * cph) / sth;
    dxdt[0] = a;
    dxdt[1] = x[3] * cph - x[4] * sph;
    dxdt[2] = x[5] - cth * a;
    const Vec3 W(x[3], x[4], x[5]);
    Vec3 Wdot;
    if constexpr (Model::has_torque) {
      Wdot = omega_rate(model, rotation(std::cos(x[0]), std::sin(x[0]), cth, sth, cph, sph), W, t);
    } else {
      Wdot = omega_rate(model, Mat3::Identity(), W, t);
    }
    dxdt[3] = Wdot.x();
    dxdt[4] = Wdot.y();
    dxdt[5] = Wdot.z();
  }

  template <class Model>
  static void jacobian(const Model& model, const Vector& x, Jacobian& J, Vector& dfdt, double t) {
    const double sth = std::sin(x[1]), cth = std::cos(x[1]);
    const double sph = std::sin(x[2]), cph = std::cos(x[2]);
    const double a = (x[3] * sph + x[4] * cph) / sth;
    const double b = x[3] * cph - x[4] * sph;
    J.setZero();
    J(0, 1) = -a * cth / sth;
    J(0, 2) = b / sth;
    J(0, 3) = sph / sth;
    J(0, 4) = cph / sth;
    J(1, 2) = -a * sth;
    J(1, 3) = cph;
    J(1, 4) = -sph;
    J(2, 1) = a / sth;
    J(2, 2) = -b * cth / sth;
    J(2, 3) = -cth * sph / sth;
    J(2, 4) = -cth * cph / sth;
    J(2, 5) = 1.0;
    const Mat3 R = rotation(std::cos(x[0]), std::sin(x[0]), cth, sth, cph, sph);
    const OmegaRateJacobian W = omega_rate_jacobian(model, R, Vec3(x[3], x[4], x[5]), t);
    Mat3 T;
    T << sth * sph, cph, 0.0,  //
        sth * cph, -sph, 0.0,  //
        cth, 0.0, 1.0;
    J.block<3, 3>(3, 0) = W.attitude * T;
    J.block<3, 3>(3, 3) = W.omega;
    dfdt = {0.0, 0.0, 0.0, W.time.x(), W.time.y(), W.time.z()};
  }

  /// No projection, no chart switch: the angles are integrated as they are.
  static bool after_step(Vector& /*x*/, Vector* /*dxdt*/, bool& /*derivative_updated*/) { return false; }
};

}  // namespace lgi::integrators::baselines
