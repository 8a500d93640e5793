#pragma once
// A magnetic dipole in a uniform field. Scene table [magnetic].
// The body carries a dipole moment μ (body frame, A m²); the field B is
// uniform and fixed in space (T). With B_b = Rᵀ B the field seen in the body,
//   V = −μ·B_b,   τ = μ × B_b
// (Jackson, Classical Electrodynamics, 3rd ed., §5.7: the torque N = m × B
// and the energy U = −m·B of a dipole in a uniform field, here in the body
// frame). V is linear in the attitude
// (linear_attitude_potential.hpp with e = B and c = −μ): τ = B_b × (−μ) =
// μ × B_b. The motion is that of a heavy top with m g χ → −μ and e3 → B: a
// compass needle is a pendulum, a spinning magnet a Lagrange top when μ is
// along a symmetry axis (tests/test_magnetic_dipole.cpp).
#include "integrators/system/terms/discrete_gradient_term.hpp"
#include "integrators/system/terms/linear_attitude_potential.hpp"

namespace lgi::system {

struct MagneticDipoleTerm {
  /// What a scene declares: [magnetic] dipole_moment (body, A m²), field (space, T).
  struct Parameters {
    Vec3 dipole_moment = Vec3::Zero();
    Vec3 field = Vec3::Zero();
  };
  static constexpr const char* scene_table = "magnetic";
  static constexpr TermTraits traits{
      .time_dependent = false, .momentum_dependent = false, .may_be_conservative = true, .linear_in_attitude = true};

  Vec3 minus_moment = Vec3::Zero();  // c = −μ
  Vec3 field = Vec3::Zero();         // B, space frame

  static MagneticDipoleTerm from_scene(const Parameters& p, const BodyProperties& /*body*/) {
    return {-p.dipole_moment, p.field};
  }

  /// B_b = Rᵀ B = Σ_k B_k (row k of R), over B's non-zero components only: the
  /// rows of the others are not read (attitude_rows). The same bits as Rᵀ B
  /// computed whole (tests/test_attitude_rows.cpp).
  Vec3 field_in_body(const Mat3& R) const {
    Vec3 out = Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      if (field(k) != 0.0) out += field(k) * R.row(k).transpose();
    return out;
  }
  /// The rows of R the torque reads: those of B's non-zero components (a
  /// vertical field, as gravity, reads row 2 only). TermTraits::attitude_rows
  /// is the bound for any field.
  unsigned attitude_rows() const {
    unsigned rows = 0;
    for (int k = 0; k < 3; ++k)
      if (field(k) != 0.0) rows |= 1u << k;
    return rows;
  }

  Vec3 torque(const Mat3& R, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/) const {
    return potential_torque(R);
  }
  Vec3 potential_torque(const Mat3& R) const { return linear_attitude::torque(field_in_body(R), minus_moment); }
  double potential(const Mat3& R) const { return minus_moment.dot(field_in_body(R)); }
  bool is_conservative() const { return true; }

  Mat3 torque_jacobian_attitude(const Mat3& R, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/) const {
    return linear_attitude::torque_jacobian_attitude(field_in_body(R), minus_moment);
  }
  Mat3 torque_jacobian_momentum(const Mat3& /*R*/, const Vec3& /*Pi*/, const Vec3& /*Omega*/, double /*t*/,
                                const Mat3& /*J_inv*/) const {
    return Mat3::Zero();
  }

  Vec3 frozen_torque(const Mat3& R, double /*t*/) const { return potential_torque(R); }
  double damping() const { return 0.0; }

  using DiscreteStart = Vec3;  // B_b at R_n
  DiscreteStart discrete_start(const Mat3& R) const { return field_in_body(R); }
  void add_discrete_torque(const DiscreteStart& b, const CayleyStep& step, DiscreteTorque& out) const {
    linear_attitude::add_discrete_torque(b, minus_moment, step, out);
  }
};

}  // namespace lgi::system
