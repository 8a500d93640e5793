#pragma once
// Baseline coordinates `matrix`: the attitude matrix in ℝ⁹ (row-major) and
// the body angular velocity, x = (R00, R01, …, R22, Ω1, Ω2, Ω3) ∈ ℝ¹².
//
//   Ṙ = R Ω̂                                   (body form of seed 002's R' = W R,
//                                               W = R Ω̂ Rᵀ the spatial spin;
//                                               seed 002: docs/sources.md)
//   Ω̇ = J⁻¹(JΩ × Ω + τ(R, JΩ, Ω, t))          (omega_dynamics.hpp)
// R is integrated as nine independent numbers: nothing keeps RᵀR = I, and the
// torque sees R as it is; /observables/orthogonality_error shows the drift.
//
// Jacobian (rosenbrock4): Ṙ is bilinear in (R, Ω):
//   ∂Ṙ_ij/∂R_ik = Ω̂_kj,   ∂Ṙ/∂Ω_m = R ê_m,
//   ∂Ω̇/∂R_ik = J⁻¹ dτ(E_ik)  (matrix_torque_differential: exact for gravity,
//                            on the rotation part of dR for the other terms).
#include <Eigen/Core>
#include <array>

#include "integrators/baselines/omega_dynamics.hpp"

namespace lgi::integrators::baselines {

struct MatrixCoordinates {
  static constexpr const char* name = "matrix";
  static constexpr std::size_t size = 12;
  static constexpr std::size_t omega_offset = 9;
  static constexpr bool euler_angle_chart = false;
  using Vector = std::array<double, size>;
  using Jacobian = Eigen::Matrix<double, 12, 12>;

  static Mat3 attitude(const Vector& x) {
    Mat3 R;
    R << x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8];
    return R;
  }

  template <class Model>
  static void from_state(const Model& model, const State& s, Vector& x) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) x[static_cast<std::size_t>(3 * i + j)] = s.R(i, j);
    const Vec3 W = model.omega(s.Pi);
    x[9] = W.x();
    x[10] = W.y();
    x[11] = W.z();
  }
  template <class Model>
  static State to_state(const Model& model, const Vector& x) {
    return {attitude(x), model.inertia.J * Vec3(x[9], x[10], x[11])};
  }
  static double singularity_margin(const Vector& /*x*/) { return 1.0; }

  template <class Model>
  static void rhs(const Model& model, const Vector& x, Vector& dxdt, double t) {
    const Mat3 R = attitude(x);
    const Vec3 W(x[9], x[10], x[11]);
    const Mat3 Rdot = R * lie::hat(W);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) dxdt[static_cast<std::size_t>(3 * i + j)] = Rdot(i, j);
    const Vec3 Wdot = omega_rate(model, R, W, t);
    dxdt[9] = Wdot.x();
    dxdt[10] = Wdot.y();
    dxdt[11] = Wdot.z();
  }

  template <class Model>
  static void jacobian(const Model& model, const Vector& x, Jacobian& J, Vector& dfdt, double t) {
    const Mat3 R = attitude(x);
    const Vec3 W(x[9], x[10], x[11]);
    const Mat3 Wh = lie::hat(W);
    J.setZero();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) J(3 * i + j, 3 * i + k) = Wh(k, j);
    for (int m = 0; m < 3; ++m) {
      const Mat3 dRdW = R * lie::hat(Vec3::Unit(m));
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) J(3 * i + j, 9 + m) = dRdW(i, j);
    }
    const OmegaRateJacobian dW = omega_rate_jacobian(model, R, W, t);
    if constexpr (Model::has_torque) {
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) {
          Mat3 E = Mat3::Zero();
          E(i, k) = 1.0;
          J.block<3, 1>(9, 3 * i + k) = model.inertia.J_inv * matrix_torque_differential(model, R, W, E, t);
        }
    }
    J.block<3, 3>(9, 9) = dW.omega;
    dfdt.fill(0.0);
    dfdt[9] = dW.time.x();
    dfdt[10] = dW.time.y();
    dfdt[11] = dW.time.z();
  }

  static bool after_step(Vector& /*x*/, Vector* /*dxdt*/, bool& derivative_updated) {
    derivative_updated = false;
    return false;
  }
};

}  // namespace lgi::integrators::baselines
