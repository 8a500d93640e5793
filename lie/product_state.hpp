#pragma once
// The product group SO(3) × ℝ³ on which every scene's state lives: the
// attitude R and a vector (the body angular momentum Π in the integrators).
// The ℝ³ factor is additive, so exp and composition act factor by factor
// (cf. manif's Bundle<SO3, R3>).
#include "lie/so3.hpp"

namespace lgi::lie {

struct SO3xR3 {
  Mat3 R = Mat3::Identity();
  Vec3 Pi = Vec3::Zero();  // the ℝ³ factor; the body angular momentum in a rigid-body state
};

/// An element (ξ, v) of the product algebra so(3) × ℝ³.
struct SO3xR3Tangent {
  Vec3 xi = Vec3::Zero();
  Vec3 v = Vec3::Zero();
};

inline SO3xR3 compose(const SO3xR3& a, const SO3xR3& b) { return {a.R * b.R, a.Pi + b.Pi}; }
inline SO3xR3 inverse(const SO3xR3& a) { return {a.R.transpose(), -a.Pi}; }
inline SO3xR3 exp_product(const SO3xR3Tangent& t) { return {exp_so3(t.xi), t.v}; }
/// Body-side retraction: (R, Π) ↦ (R exp(ξ), Π + v).
inline SO3xR3 retract_body(const SO3xR3& s, const SO3xR3Tangent& t) {
  return {s.R * exp_so3(t.xi), s.Pi + t.v};
}

}  // namespace lgi::lie
