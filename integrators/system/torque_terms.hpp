#pragma once
// Torque terms a scene may declare. Each term gives its body torque
// τ(R, Π, t) and, when it derives from a potential, V(R). A scene's model is
// assembled from only the terms it declares (rigid_body.hpp), so a free body
// evaluates no torque at all.
//
// Conventions (docs/conventions.md §4): gravity along −e3 in space, Γ = Rᵀ e3,
// V = m g χ·Γ, τ = m g Γ × χ. Torques are in body coordinates.
//
// Jacobians (for implicit schemes, integrators/implicit_rkmk.hpp). Each term
// also gives the derivatives of its torque at (R, Π, t):
//   torque_jacobian_attitude(R, Π, Ω, t)        = ∂τ/∂η at η = 0 for the
//       body-side perturbation R → R exp(η̂) (the same trivialisation as the
//       schemes' R_i = R_n exp(w_i));
//   torque_jacobian_momentum(R, Π, Ω, t, J⁻¹)   = dτ/dΠ, the total derivative
//       with Ω = J⁻¹Π following Π (so a damper −cΩ gives −c J⁻¹).
// The scene terms have exact closed forms (below); only the generic
// TimeDependentTorque callable falls back to central differences.
// tests/test_model_jacobian.cpp checks every term against central differences.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "integrators/system/inertia.hpp"
#include "lie/so3.hpp"

namespace lgi::system {

/// Uniform gravity on a body with centre of mass χ (body coordinates, from
/// the fixed point), any direction: the general heavy top.
struct GravityTerm {
  double mass = 0.0;
  double g = 0.0;
  Vec3 center_of_mass = Vec3::Zero();  // χ
  Vec3 mg_chi = Vec3::Zero();          // m g χ, precomputed per run

  GravityTerm() = default;
  GravityTerm(double m, double g_, const Vec3& chi) : mass(m), g(g_), center_of_mass(chi), mg_chi(m * g_ * chi) {}

  static constexpr bool conservative = true;
  static constexpr bool time_dependent = false;
  static Vec3 vertical_in_body(const Mat3& R) { return R.row(2).transpose(); }  // Γ = Rᵀ e3
  Vec3 torque(const Mat3& R, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/) const {
    return vertical_in_body(R).cross(mg_chi);
  }
  double potential(const Mat3& R) const { return mg_chi.dot(vertical_in_body(R)); }

  /// Γ(R exp(η̂)) = exp(−η̂) Γ = Γ + Γ × η + O(η²), so
  /// δτ = (Γ × η) × m g χ = −(m g χ)^ Γ̂ η:  ∂τ/∂η = −(m g χ)^ Γ̂.
  Mat3 torque_jacobian_attitude(const Mat3& R, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/) const {
    return -lie::hat(mg_chi) * lie::hat(vertical_in_body(R));
  }
  /// Gravity does not depend on Π.
  Mat3 torque_jacobian_momentum(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/,
                                const Mat3& /*J_inv*/) const {
    return Mat3::Zero();
  }
};

/// Torsional spring and damper to a fixed attitude R_rest:
/// τ = −k log(R_restᵀ R) − c Ω, V = ½ k |log(R_restᵀ R)|².
struct SpringTerm {
  double stiffness = 0.0;  // k, N m / rad
  double damping = 0.0;    // c, N m s / rad
  Mat3 rest = Mat3::Identity();
  Mat3 rest_transpose = Mat3::Identity();

  SpringTerm() = default;
  SpringTerm(double k, double c, const Mat3& R_rest) : stiffness(k), damping(c), rest(R_rest), rest_transpose(R_rest.transpose()) {}

  static constexpr bool conservative = false;  // when damping > 0; see is_conservative()
  static constexpr bool time_dependent = false;
  bool is_conservative() const { return damping == 0.0; }
  Vec3 deflection(const Mat3& R) const { return lie::log_so3(rest_transpose * R); }
  Vec3 torque(const Mat3& R, const Vec3& /*Pi*/, const Vec3& Omega, double /*t*/) const {
    return -stiffness * deflection(R) - damping * Omega;
  }
  double potential(const Mat3& R) const { return 0.5 * stiffness * deflection(R).squaredNorm(); }

  /// With ξ = log(R_restᵀ R): exp(ξ + δξ) = exp(ξ) exp(η̂) to first order
  /// gives η = dexp_body(ξ) δξ (so3.hpp's body trivialisation), hence
  /// δξ = dexp⁻¹_body(ξ) η and ∂τ/∂η = −k dexp⁻¹_body(ξ)
  /// (= −k (I + ½ ξ̂ + c(|ξ|) ξ̂²), docs/math.md §1). Valid for |ξ| < π, where log
  /// is smooth; at |ξ| = π the torque itself jumps (the principal branch).
  Mat3 torque_jacobian_attitude(const Mat3& R, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/) const {
    return -stiffness * lie::dexpinv_body_matrix(deflection(R));
  }
  /// The damper −c Ω = −c J⁻¹ Π: dτ/dΠ = −c J⁻¹.
  Mat3 torque_jacobian_momentum(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/,
                                const Mat3& J_inv) const {
    return -damping * J_inv;
  }
};

/// A body-fixed harmonic drive, τ(t) = A sin(ω t + φ): the scene files'
/// `[drive]` table, and the shipped example of a time-dependent torque.
struct HarmonicDriveTerm {
  Vec3 amplitude = Vec3::Zero();  // A, N m, body frame
  double angular_frequency = 0.0; // ω, rad/s
  double phase = 0.0;             // φ, rad

  static constexpr bool conservative = false;
  static constexpr bool time_dependent = true;
  Vec3 torque(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double t) const {
    return amplitude * std::sin(angular_frequency * t + phase);
  }
  double potential(const Mat3& /*R*/) const { return 0.0; }

  /// τ depends on t only.
  Mat3 torque_jacobian_attitude(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/) const {
    return Mat3::Zero();
  }
  Mat3 torque_jacobian_momentum(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/,
                                const Mat3& /*J_inv*/) const {
    return Mat3::Zero();
  }
};

/// The hook for any other time-dependent torque: a callable
/// f(t, R, Π, Ω) → body torque, stored by value (no std::function, so the
/// stage loop stays free of indirect calls).
template <class F>
struct TimeDependentTorque {
  F f;
  static constexpr bool conservative = false;
  static constexpr bool time_dependent = true;
  Vec3 torque(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const { return f(t, R, Pi, Omega); }
  double potential(const Mat3& /*R*/) const { return 0.0; }

  /// A user callable has no closed-form derivative: central differences
  /// (step ε^(1/3) scaled, error O(ε^(2/3)) ≈ 1e-11 relative), which is
  /// ample for a Newton matrix. Perturbs R → R exp(±δ e_j).
  Mat3 torque_jacobian_attitude(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    const double d = std::cbrt(std::numeric_limits<double>::epsilon());
    Mat3 out;
    for (int j = 0; j < 3; ++j) {
      const Vec3 e = d * Vec3::Unit(j);
      out.col(j) = (f(t, Mat3(R * lie::exp_so3(e)), Pi, Omega) - f(t, Mat3(R * lie::exp_so3(-e)), Pi, Omega)) / (2.0 * d);
    }
    return out;
  }
  /// Central differences in Π with Ω = J⁻¹Π moving along.
  Mat3 torque_jacobian_momentum(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t, const Mat3& J_inv) const {
    const double d = std::cbrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, Pi.norm());
    Mat3 out;
    for (int j = 0; j < 3; ++j) {
      const Vec3 e = d * Vec3::Unit(j);
      const Vec3 de = J_inv * e;
      out.col(j) = (f(t, R, Vec3(Pi + e), Vec3(Omega + de)) - f(t, R, Vec3(Pi - e), Vec3(Omega - de))) / (2.0 * d);
    }
    return out;
  }
};
template <class F>
TimeDependentTorque(F) -> TimeDependentTorque<F>;

}  // namespace lgi::system
