#pragma once
// A term whose torque, at frozen attitude R and time t, is affine in Ω with a
// scalar damper: τ = f(R, t) − c Ω. Then the kick Ṙ = 0, Π̇ = Σ τ is a linear
// ODE in Π with a closed-form flow (integrators/schemes/splitting.hpp).
#include <concepts>

#include "integrators/system/terms/torque_term.hpp"

namespace lgi::system {

template <class T>
concept FrozenKickTerm = TorqueTerm<T> && requires(const T& term, const Mat3& R, double t) {
  { term.frozen_torque(R, t) } -> std::same_as<Vec3>;  // f(R, t)
  { term.damping() } -> std::convertible_to<double>;   // c ≥ 0
};

}  // namespace lgi::system
