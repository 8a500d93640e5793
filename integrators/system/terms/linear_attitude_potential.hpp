#pragma once
// The algebra shared by potentials linear in the attitude, V = c·b with
// b = Rᵀe the body view of a space-fixed vector e and c a body vector
// (gravity: e = e3, c = m g χ; a magnetic dipole: e = B, c = −μ).
//   τ = b × c;
//   b(R exp(η̂)) = exp(−η̂) b = b + b × η + O(η²), so ∂τ/∂η = −ĉ b̂;
//   Cayley step (integrators/schemes/simo_wong.hpp): b_{n+1} = cay(ξ)ᵀ b_n, whose
//   midpoint is b_mid = (I + ξ̂/2)⁻¹ b_n; τ_d = b_mid × c gives
//   τ_d·ξ = −c·(b_{n+1} − b_n) exactly, and −h ∂τ_d/∂W = (h²/2) ĉ (I + ξ̂/2)⁻¹ b̂_mid.
#include "integrators/system/terms/discrete_gradient_term.hpp"
#include "lie/so3.hpp"

namespace lgi::system::linear_attitude {

inline Vec3 torque(const Vec3& b, const Vec3& c) { return b.cross(c); }
inline Mat3 torque_jacobian_attitude(const Vec3& b, const Vec3& c) { return -lie::hat(c) * lie::hat(b); }

inline void add_discrete_torque(const Vec3& b_start, const Vec3& c, const CayleyStep& step, DiscreteTorque& out) {
  const Vec3 b_mid = step.Ainv * b_start;
  out.tau += b_mid.cross(c);
  out.magnitude += b_mid.norm() * c.norm();
  out.jacobian += (0.5 * step.h * step.h) * (lie::hat(c) * step.Ainv * lie::hat(b_mid));
}

}  // namespace lgi::system::linear_attitude
