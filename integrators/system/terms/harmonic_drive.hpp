#pragma once
// A body-fixed harmonic drive, τ(t) = A sin(ω t + φ). Scene table [drive].
// No potential; τ depends on t only.
#include <cmath>

#include "integrators/system/terms/discrete_gradient_term.hpp"

namespace lgi::system {

struct HarmonicDriveTerm {
  /// What a scene declares: [drive] torque_amplitude, angular_frequency, phase.
  struct Parameters {
    Vec3 torque_amplitude = Vec3::Zero();  // A, N m, body frame
    double angular_frequency = 0.0;        // ω, rad/s
    double phase = 0.0;                    // φ, rad
  };
  static constexpr const char* scene_table = "drive";
  static constexpr TermTraits traits{
      .time_dependent = true, .momentum_dependent = false, .may_be_conservative = false, .linear_in_attitude = false,
      .attitude_rows = 0};  // τ does not depend on R

  Vec3 amplitude = Vec3::Zero();
  double angular_frequency = 0.0;
  double phase = 0.0;

  static HarmonicDriveTerm from_scene(const Parameters& p, const BodyProperties& /*body*/) {
    return {p.torque_amplitude, p.angular_frequency, p.phase};
  }

  Vec3 torque(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double t) const {
    return amplitude * std::sin(angular_frequency * t + phase);
  }
  Vec3 potential_torque(const Mat3& /*R*/) const { return Vec3::Zero(); }
  double potential(const Mat3& /*R*/) const { return 0.0; }
  bool is_conservative() const { return false; }

  Mat3 torque_jacobian_attitude(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/) const {
    return Mat3::Zero();
  }
  Mat3 torque_jacobian_momentum(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/,
                                const Mat3& /*J_inv*/) const {
    return Mat3::Zero();
  }
  /// ∂τ/∂t = A ω cos(ω t + φ).
  Vec3 torque_time_derivative(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double t) const {
    return amplitude * (angular_frequency * std::cos(angular_frequency * t + phase));
  }

  // Frozen kick: τ(t) at the frozen time.
  Vec3 frozen_torque(const Mat3& R, double t) const { return torque(R, Vec3::Zero(), Vec3::Zero(), t); }
  double damping() const { return 0.0; }

  // Discrete torque: τ at the midpoint time.
  struct DiscreteStart {};
  DiscreteStart discrete_start(const Mat3& /*R*/) const { return {}; }
  void add_discrete_torque(const DiscreteStart& /*start*/, const CayleyStep& step, DiscreteTorque& out) const {
    const Vec3 drive = torque(*step.R, Vec3::Zero(), step.W, step.t_mid);
    out.tau += drive;
    out.magnitude += drive.norm();
  }
};

}  // namespace lgi::system
