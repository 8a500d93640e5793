#pragma once
// The rigid body with a fixed point (or free), in body form on SO(3) × ℝ³:
//   Ṙ = R Ω̂,  Π̇ = Π × Ω + τ(R, Π, t),  Ω = J⁻¹ Π        (Euler–Poisson)
// (conventions.md; Holm, Geometric Mechanics I, §6; seed 003).
// The model is a variadic template over the torque terms the scene declares,
// so the torque is a fold over exactly those terms, resolved at compile time.
#include <tuple>
#include <type_traits>

#include "integrators/system/inertia.hpp"
#include "integrators/system/torque_terms.hpp"
#include "lie/product_state.hpp"

namespace lgi::system {

using State = lie::SO3xR3;  // (R, Π): attitude and body angular momentum

template <class... Terms>
struct RigidBody {
  Inertia inertia;
  std::tuple<Terms...> terms;

  static constexpr bool has_torque = sizeof...(Terms) > 0;
  static constexpr bool time_dependent = (Terms::time_dependent || ... || false);

  Vec3 omega(const Vec3& Pi) const { return inertia.J_inv * Pi; }

  /// Body torque, the sum of the declared terms (zero for a free body, at no cost).
  Vec3 torque(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    if constexpr (!has_torque) {
      return Vec3::Zero();
    } else {
      // The lambda returns Vec3, not an Eigen expression that would outlive its operands.
      return std::apply([&](const auto&... term) -> Vec3 { return (term.torque(R, Pi, Omega, t) + ...); }, terms);
    }
  }

  /// Π̇ = Π × Ω + τ.
  Vec3 momentum_rate(const Mat3& R, const Vec3& Pi, const Vec3& Omega, double t) const {
    if constexpr (!has_torque) {
      return Pi.cross(Omega);
    } else {
      return Pi.cross(Omega) + torque(R, Pi, Omega, t);
    }
  }

  double kinetic_energy(const Vec3& Pi) const { return 0.5 * Pi.dot(omega(Pi)); }
  double potential_energy(const Mat3& R) const {
    if constexpr (!has_torque) {
      return 0.0;
    } else {
      return std::apply([&](const auto&... term) { return (term.potential(R) + ...); }, terms);
    }
  }
  /// H = ½ Π·J⁻¹Π + V(R).
  double energy(const State& s) const { return kinetic_energy(s.Pi) + potential_energy(s.R); }

  template <class T>
  static constexpr bool has_term = (std::is_same_v<T, Terms> || ... || false);
  template <class T>
  const T& term() const { return std::get<T>(terms); }
};

using FreeBody = RigidBody<>;

}  // namespace lgi::system
