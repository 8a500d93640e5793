#pragma once
// Uniform gravity on a body with centre of mass χ (body coordinates, from the
// fixed point), any direction: the general heavy top. Scene table [gravity].
// docs/conventions.md §4: gravity along −e3 in space, Γ = Rᵀe3,
//   V = m g χ·Γ,   τ = m g Γ × χ = Γ × (m g χ).
// V is linear in the attitude (linear_attitude_potential.hpp with e = e3,
// c = m g χ), so every capability has a closed form.
#include <optional>

#include "integrators/system/terms/discrete_gradient_term.hpp"
#include "integrators/system/terms/linear_attitude_potential.hpp"

namespace lgi::system {

struct GravityTerm {
  /// What a scene declares: [gravity] g (m/s²); mass and χ come from [body].
  struct Parameters {
    double g = 9.81;
  };
  static constexpr const char* scene_table = "gravity";
  static constexpr TermTraits traits{
      .time_dependent = false, .momentum_dependent = false, .may_be_conservative = true, .linear_in_attitude = true,
      .attitude_rows = 0b100};  // Γ = Rᵀe3 is row 2 of R

  double mass = 0.0;
  double g = 0.0;
  Vec3 center_of_mass = Vec3::Zero();  // χ
  Vec3 mg_chi = Vec3::Zero();          // m g χ, precomputed

  GravityTerm() = default;
  GravityTerm(double m, double g_, const Vec3& chi) : mass(m), g(g_), center_of_mass(chi), mg_chi(m * g_ * chi) {}
  static GravityTerm from_scene(const Parameters& p, const BodyProperties& body) {
    return {body.mass, p.g, body.center_of_mass};
  }

  static Vec3 vertical_in_body(const Mat3& R) { return R.row(2).transpose(); }  // Γ = Rᵀ e3

  Vec3 torque(const Mat3& R, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/) const {
    return potential_torque(R);
  }
  Vec3 potential_torque(const Mat3& R) const { return linear_attitude::torque(vertical_in_body(R), mg_chi); }
  double potential(const Mat3& R) const { return mg_chi.dot(vertical_in_body(R)); }
  bool is_conservative() const { return true; }

  Mat3 torque_jacobian_attitude(const Mat3& R, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/) const {
    return linear_attitude::torque_jacobian_attitude(vertical_in_body(R), mg_chi);
  }
  Mat3 torque_jacobian_momentum(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/,
                                const Mat3& /*J_inv*/) const {
    return Mat3::Zero();
  }

  // Frozen kick: τ does not depend on Ω.
  Vec3 frozen_torque(const Mat3& R, double /*t*/) const { return potential_torque(R); }
  double damping() const { return 0.0; }

  // Discrete torque: Γ_mid = (I + ξ̂/2)⁻¹ Γ_n.
  using DiscreteStart = Vec3;  // Γ_n
  DiscreteStart discrete_start(const Mat3& R) const { return vertical_in_body(R); }
  void add_discrete_torque(const DiscreteStart& gamma, const CayleyStep& step, DiscreteTorque& out) const {
    linear_attitude::add_discrete_torque(gamma, mg_chi, step, out);
  }
};

}  // namespace lgi::system
