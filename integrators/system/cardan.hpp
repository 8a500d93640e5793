#pragma once
// The Cardan-suspended top (docs/cardan.md): a rigid body in a gimbal of two
// rings. The outer ring turns by q1 about an axis fixed in space, tilted by α
// from the vertical; the inner ring turns by q2 in it about the outer ring's
// e1; the body turns by q3 in the inner ring about the inner ring's e3:
//   R(q) = Ry(α) Rz(q1) Rx(q2) Rz(q3)              (docs/cardan.md, eq. (1))
// With α = 0 the Cardan angles are the ZXZ Euler angles of
// docs/conventions.md (ψ, θ, φ) = (q1, q2, q3).
//
// Configuration space T³, state (q, p) ∈ T³ × ℝ³ with p the momenta
// conjugate to q (docs/cardan.md §3 says why not (q, q̇)). The angles are
// carried unwrapped, on the universal cover ℝ³ of T³: T³ is abelian, its
// exponential is q ↦ q mod 2π, so no chart is ever needed.
//
//   T = ½ q̇ᵀ M(q) q̇,  M(q) = Eᵀ J E + Fᵀ K F + C_o e1 e1ᵀ        (eq. (4))
//   E(q) = [[s2 s3, c3, 0], [s2 c3, −s3, 0], [c2, 0, 1]]  (body Ω = E q̇)
//   F(q) = [[0, 1, 0], [s2, 0, 0], [c2, 0, 0]]            (inner ring ω = F q̇)
//   V(q) = g γ·(Rz(q1)[Rx(q2)(Rz(q3) m χ + m_i c_i) + m_o c_o]),  γ = Ry(α)ᵀ e3   (eq. (5))
//   H(q, p) = ½ pᵀ M⁻¹ p + V,
//   q̇ = M⁻¹ p,  ṗ_k = ½ vᵀ (∂M/∂q_k) v − ∂V/∂q_k,  v = M⁻¹ p            (eq. (7))
// J is the body's inertia about the fixed point, K = diag(A_i, B_i, C_i)
// the inner ring's (A_i about its axis e1, C_i about the body axis e3),
// C_o the outer ring's moment about its own axis. M does not depend on q1;
// V does only through the tilt (or never, for α = 0): then p1 is an integral.
#include <array>

#include "lie/so3.hpp"
#include "lie/product_state.hpp"
#include "integrators/system/torus_state.hpp"

namespace lgi::system {

using lie::Mat3;
using lie::Vec3;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// The suspension of a scene's [suspension] table (docs/cardan.md §6).
struct SuspensionParameters {
  double tilt = 0.0;                    // α ∈ [0, π]: outer axis from the vertical, in the (e1, e3) plane
  double outer_inertia = 0.0;           // C_o ≥ 0: the outer ring's moment about its axis
  Vec3 inner_inertia = Vec3::Zero();    // (A_i, B_i, C_i) ≥ 0: the inner ring's principal moments in its frame
  double outer_mass = 0.0;              // ≥ 0
  Vec3 outer_center = Vec3::Zero();     // the outer ring's centre of mass in its frame, from the fixed point
  double inner_mass = 0.0;              // ≥ 0
  Vec3 inner_center = Vec3::Zero();     // the inner ring's, in its frame
};


inline Vec6 stack(const TorusState& s) {
  Vec6 x;
  x << s.q, s.p;
  return x;
}
inline TorusState unstack(const Vec6& x) { return {x.head<3>(), x.tail<3>()}; }

/// The Cardan top's model: M(q), V(q), H and the canonical field (eq. (7)).
struct CardanTop {
  using state_type = TorusState;  // the time loop's state (integrators/core/state_space.hpp)
  Mat3 J = Mat3::Identity();  // the body's inertia about the fixed point
  double mass = 0.0;          // the body's
  Vec3 chi = Vec3::Zero();    // the body's centre of mass, body frame
  double g = 0.0;             // gravity along −e3 in space
  SuspensionParameters suspension{};

  /// Ry(α): the pedestal frame in which the outer ring turns about e3.
  Mat3 pedestal() const;
  /// R(q) of eq. (1): the body's attitude in space.
  Mat3 attitude(const Vec3& q) const;
  /// E(q): body Ω = E(q) q̇ (eq. (2)).
  static Mat3 body_rate_matrix(const Vec3& q);
  /// M(q) of eq. (4).
  Mat3 mass_matrix(const Vec3& q) const;
  /// ∂M/∂q_k (k = 0, 1, 2; ∂M/∂q1 = 0).
  std::array<Mat3, 3> mass_matrix_derivatives(const Vec3& q) const;
  double potential(const Vec3& q) const;
  Vec3 potential_gradient(const Vec3& q) const;

  /// q̇ = M⁻¹ p.
  Vec3 velocity(const TorusState& s) const;
  double energy(const TorusState& s) const;
  /// (∂H/∂q, ∂H/∂p).
  Vec6 energy_gradient(const TorusState& s) const;
  /// The canonical field (q̇, ṗ) = (∂H/∂p, −∂H/∂q).
  Vec6 field(const TorusState& s) const;
  /// Its Jacobian ∂f/∂x, x = (q, p), by central differences of field()
  /// (step 1e-6 relative; for the Newton iterations of the implicit
  /// schemes, whose converged result does not depend on it).
  Mat6 field_jacobian(const TorusState& s) const;

  /// The body's (R, Π) for the SO(3) outputs: R(q) and Π = J E(q) q̇.
  lie::SO3xR3 body_state(const TorusState& s) const;
  /// The momenta p = M(q) q̇ from rates.
  TorusState from_rates(const Vec3& q, const Vec3& qdot) const { return {q, mass_matrix(q) * qdot}; }
  /// Whether p1 is an integral: vertical outer axis (α = 0), or no potential at all.
  bool outer_angle_cyclic() const;
};

}  // namespace lgi::system
