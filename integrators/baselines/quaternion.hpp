#pragma once
// Baseline coordinates `quat` and `quat-normalized`: the quaternion
// q = (w, x, y, z) (scalar first, docs/conventions.md §1) and the body angular
// velocity, x = (w, x, y, z, Ω1, Ω2, Ω3) ∈ ℝ⁷.
//
//   q̇ = ½ q ⊗ (0, Ω) = ½ (−v·Ω, w Ω + v × Ω)         (v = (x, y, z))
//   Ω̇ = J⁻¹(JΩ × Ω + τ(R(q/|q|), JΩ, Ω, t))         (omega_dynamics.hpp)
// The torque sees the attitude q represents, R(q/|q|) (lie::matrix_from_quat
// of the normalised copy; q itself is left alone). Nothing in the equations
// keeps |q| = 1: the exact flow does, a numerical one drifts.
//
// `quat` never touches |q|. For the observer, R is the matrix of the map
// v ↦ q v q* (docs/conventions.md §1: v_space = q v q*), which for |q| ≠ 1 is
// |q|² R(q/|q|): the file's /observables/orthogonality_error, |RᵀR − I|_F,
// is then √3 ||q|⁴ − 1| ≈ 4√3 ||q| − 1|, the drift itself, whatever the
// attitude. (Energy and the other observables see the same R.)
// `quat-normalized` projects: q ← q/|q| after every accepted step, a named
// projection (never a hidden one). Because q̇ is linear in q and Ω̇ depends
// only on q/|q|, the derivative of the projected state is the old one with
// its q-part scaled by 1/|q|: an FSAL stepper keeps its derivative.
//
// Jacobian (rosenbrock4):
//   ∂q̇/∂q = ½ [[0, −Ωᵀ], [Ω, −Ω̂]],   ∂q̇/∂Ω = ½ [[−vᵀ], [w I + v̂]],
//   ∂Ω̇/∂q = (∂Ω̇/∂η) M,  M = (2/|q|) [−v̂q, ŵ I − (v̂q)^]   (q̂ = q/|q| = (ŵ, v̂q)),
// since q̂ + dq̂ = q̂ ⊗ (1, η/2) with η = 2 vec(q̂* ⊗ dq)/|q| (the radial part of
// dq does not move the attitude: M q = 0).
#include <Eigen/Core>
#include <array>
#include <cmath>

#include "integrators/baselines/omega_dynamics.hpp"
#include "lie/quaternion.hpp"

namespace lgi::integrators::baselines {

template <bool Normalized>
struct QuaternionCoordinates {
  static constexpr const char* name = Normalized ? "quat-normalized" : "quat";
  static constexpr std::size_t size = 7;
  static constexpr std::size_t omega_offset = 4;
  static constexpr bool euler_angle_chart = false;
  using Vector = std::array<double, size>;
  using Jacobian = Eigen::Matrix<double, 7, 7>;

  static Eigen::Quaterniond quaternion(const Vector& x) { return Eigen::Quaterniond(x[0], x[1], x[2], x[3]); }
  static double norm(const Vector& x) { return std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3]); }

  /// The attitude q represents: R(q/|q|).
  static Mat3 attitude(const Vector& x) { return lie::matrix_from_quat(quaternion(x).normalized()); }
  /// The matrix of v ↦ q v q*: |q|² R(q/|q|).
  static Mat3 sandwich_matrix(const Vector& x) {
    const Eigen::Quaterniond q = quaternion(x);
    return q.squaredNorm() * lie::matrix_from_quat(q.normalized());
  }

  template <class Model>
  static void from_state(const Model& model, const State& s, Vector& x) {
    const Eigen::Quaterniond q = lie::quat_from_matrix(s.R);
    const Vec3 W = model.omega(s.Pi);
    x = {q.w(), q.x(), q.y(), q.z(), W.x(), W.y(), W.z()};
  }
  template <class Model>
  static State to_state(const Model& model, const Vector& x) {
    return {sandwich_matrix(x), model.inertia.J * Vec3(x[4], x[5], x[6])};
  }
  static double singularity_margin(const Vector& /*x*/) { return 1.0; }  // no singular set

  template <class Model>
  static void rhs(const Model& model, const Vector& x, Vector& dxdt, double t) {
    const double w = x[0];
    const Vec3 v(x[1], x[2], x[3]);
    const Vec3 W(x[4], x[5], x[6]);
    const Vec3 vdot = 0.5 * (w * W + v.cross(W));
    dxdt[0] = -0.5 * v.dot(W);
    dxdt[1] = vdot.x();
    dxdt[2] = vdot.y();
    dxdt[3] = vdot.z();
    Vec3 Wdot;
    if constexpr (Model::has_torque) {
      Wdot = omega_rate(model, attitude(x), W, t);
    } else {
      Wdot = omega_rate(model, Mat3::Identity(), W, t);
    }
    dxdt[4] = Wdot.x();
    dxdt[5] = Wdot.y();
    dxdt[6] = Wdot.z();
  }

  template <class Model>
  static void jacobian(const Model& model, const Vector& x, Jacobian& J, Vector& dfdt, double t) {
    const double w = x[0];
    const Vec3 v(x[1], x[2], x[3]);
    const Vec3 W(x[4], x[5], x[6]);
    J.setZero();
    J.block<1, 3>(0, 1) = -0.5 * W.transpose();
    J.block<3, 1>(1, 0) = 0.5 * W;
    J.block<3, 3>(1, 1) = -0.5 * lie::hat(W);
    J.block<1, 3>(0, 4) = -0.5 * v.transpose();
    J.block<3, 3>(1, 4) = 0.5 * (w * Mat3::Identity() + lie::hat(v));
    const double n = norm(x);
    const double wn = w / n;
    const Vec3 vn = v / n;
    Eigen::Matrix<double, 3, 4> M;
    M.col(0) = -2.0 / n * vn;
    M.block<3, 3>(0, 1) = 2.0 / n * (wn * Mat3::Identity() - lie::hat(vn));
    const OmegaRateJacobian dW = omega_rate_jacobian(model, attitude(x), W, t);
    J.block<3, 4>(4, 0) = dW.attitude * M;
    J.block<3, 3>(4, 4) = dW.omega;
    dfdt = {0.0, 0.0, 0.0, 0.0, dW.time.x(), dW.time.y(), dW.time.z()};
  }

  /// `quat-normalized`: q ← q/|q|, and the q-part of the derivative scaled
  /// the same way (exact, see above). `quat`: nothing.
  static bool after_step(Vector& x, Vector* dxdt, bool& derivative_updated) {
    derivative_updated = false;
    if constexpr (!Normalized) {
      return false;
    } else {
      const double f = 1.0 / norm(x);
      for (std::size_t i = 0; i < 4; ++i) x[i] *= f;
      if (dxdt) {
        for (std::size_t i = 0; i < 4; ++i) (*dxdt)[i] *= f;
        derivative_updated = true;
      }
      return true;
    }
  }
};

using QuatCoordinates = QuaternionCoordinates<false>;
using QuatNormalizedCoordinates = QuaternionCoordinates<true>;

}  // namespace lgi::integrators::baselines
