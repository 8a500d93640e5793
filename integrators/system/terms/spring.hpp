#pragma once
// Torsional spring and damper to a fixed attitude R_rest. Scene table [spring].
//   τ = −k ξ − c Ω,  ξ = log(R_restᵀ R),   V = ½ k |ξ|²
// (the damper −cΩ is not from a potential: conservative only for c = 0).
#include <cmath>
#include <limits>

#include "integrators/system/terms/discrete_gradient_term.hpp"
#include "lie/so3.hpp"

namespace lgi::system {

struct SpringTerm {
  /// What a scene declares: [spring] stiffness, damping, rest_quaternion.
  struct Parameters {
    double stiffness = 0.0;  // k, N m / rad
    double damping = 0.0;    // c, N m s / rad
    Mat3 rest = Mat3::Identity();
  };
  static constexpr const char* scene_table = "spring";
  static constexpr TermTraits traits{
      .time_dependent = false, .momentum_dependent = true, .may_be_conservative = true, .linear_in_attitude = false};

  double stiffness = 0.0;
  double damping_coefficient = 0.0;
  Mat3 rest = Mat3::Identity();
  Mat3 rest_transpose = Mat3::Identity();

  SpringTerm() = default;
  SpringTerm(double k, double c, const Mat3& R_rest)
      : stiffness(k), damping_coefficient(c), rest(R_rest), rest_transpose(R_rest.transpose()) {}
  static SpringTerm from_scene(const Parameters& p, const BodyProperties& /*body*/) {
    return {p.stiffness, p.damping, p.rest};
  }

  Vec3 deflection(const Mat3& R) const { return lie::log_so3(rest_transpose * R); }
  Vec3 torque(const Mat3& R, const Vec3& /*Pi*/, const Vec3& Omega, double /*t*/) const {
    return -stiffness * deflection(R) - damping_coefficient * Omega;
  }
  Vec3 potential_torque(const Mat3& R) const { return -stiffness * deflection(R); }
  double potential(const Mat3& R) const { return 0.5 * stiffness * deflection(R).squaredNorm(); }
  bool is_conservative() const { return damping_coefficient == 0.0; }

  /// With ξ = log(R_restᵀ R): exp(ξ + δξ) = exp(ξ) exp(η̂) to first order
  /// gives η = dexp_body(ξ) δξ, hence ∂τ/∂η = −k dexp⁻¹_body(ξ)
  /// (docs/math.md §1). Valid for |ξ| < π, where log is smooth.
  Mat3 torque_jacobian_attitude(const Mat3& R, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/) const {
    return -stiffness * lie::dexpinv_body_matrix(deflection(R));
  }
  /// The damper −c Ω = −c J⁻¹ Π: dτ/dΠ = −c J⁻¹.
  Mat3 torque_jacobian_momentum(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/,
                                const Mat3& J_inv) const {
    return -damping_coefficient * J_inv;
  }

  // Frozen kick: f = −k ξ(R), damper c.
  Vec3 frozen_torque(const Mat3& R, double /*t*/) const { return potential_torque(R); }
  double damping() const { return damping_coefficient; }

  // Discrete torque (integrators/schemes/simo_wong.hpp derives it):
  //   τ_s = τ_m + σ ξ − c W,  τ_m = −k log(R_restᵀ R_m),  R_m = R_n cay(η),
  //   η = ξ/(1 + √(1 + |ξ|²/4)) (cay(η)² = cay(ξ): the geodesic midpoint),
  //   σ = (−[V(R_{n+1}) − V(R_n)] − τ_m·ξ)/|ξ|² (Gonzalez's midpoint discrete
  //   gradient), set to 0 where the bracket is below its own rounding.
  using DiscreteStart = double;  // V(R_n)
  DiscreteStart discrete_start(const Mat3& R) const { return potential(R); }
  void add_discrete_torque(const DiscreteStart& V0, const CayleyStep& step, DiscreteTorque& out) const;
};

inline void SpringTerm::add_discrete_torque(const DiscreteStart& V0, const CayleyStep& step,
                                            DiscreteTorque& out) const {
  const double k = stiffness;
  const Vec3& xi = step.xi;
  const double theta2 = step.theta2;
  const double h = step.h;
  const Vec3 delta1 = deflection(step.R1);
  const double V1 = 0.5 * k * delta1.squaredNorm();  // = potential(R1), bit for bit
  const double r = std::sqrt(1.0 + 0.25 * theta2);
  const Vec3 eta = xi / (1.0 + r);
  const Vec3 delta_m = deflection(Mat3(*step.R * lie::cay(eta)));
  const double power = k * delta_m.dot(xi);  // −τ_m·ξ
  const double num = -(V1 - V0) + power;
  const double noise = 16.0 * std::numeric_limits<double>::epsilon() * (V0 + V1 + std::abs(power));
  const double sigma = theta2 > 0.0 && std::abs(num) > noise ? num / theta2 : 0.0;
  out.tau += -k * delta_m + sigma * xi;
  out.magnitude += k * delta_m.norm() + std::abs(sigma) * std::sqrt(theta2);
  if (sigma != 0.0) out.noise += std::abs(h) * noise / std::sqrt(theta2);
  // ∂τ_s/∂ξ, with ∂δ_m/∂ξ = dexp⁻¹_body(δ_m) dcay_body(η) [I/(1+r) − ξξᵀ/(4r(1+r)²)].
  const Mat3 E_eta = Mat3::Identity() / (1.0 + r) - (xi * xi.transpose()) / (4.0 * r * (1.0 + r) * (1.0 + r));
  const Mat3 Dm = lie::dexpinv_body_matrix(delta_m) * lie::dcay_body(eta) * E_eta;
  Mat3 dtau = -k * Dm;
  if (sigma != 0.0) {
    const Mat3 D1 = lie::dexpinv_body_matrix(delta1) * lie::dcay_body(xi);
    const Eigen::RowVector3d dnum = -k * delta1.transpose() * D1 + k * xi.transpose() * Dm + k * delta_m.transpose();
    const Eigen::RowVector3d dsigma = (dnum - 2.0 * sigma * xi.transpose()) / theta2;
    dtau += xi * dsigma + sigma * Mat3::Identity();
  }
  out.jacobian -= (h * h) * dtau;
  if (damping_coefficient != 0.0) {
    out.tau -= damping_coefficient * step.W;
    out.magnitude += damping_coefficient * step.W.norm();
    out.jacobian += (h * damping_coefficient) * Mat3::Identity();
  }
}

}  // namespace lgi::system
