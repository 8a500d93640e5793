#pragma once
// Torque terms a scene may declare. Each term gives its body torque
// τ(R, Π, t) and, when it derives from a potential, V(R). A scene's model is
// assembled from only the terms it declares (rigid_body.hpp), so a free body
// evaluates no torque at all.
//
// Conventions (conventions.md): gravity along −e3 in space, Γ = Rᵀ e3,
// V = m g χ·Γ, τ = m g Γ × χ. Torques are in body coordinates.
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
};
template <class F>
TimeDependentTorque(F) -> TimeDependentTorque<F>;

}  // namespace lgi::system
