#pragma once
// The inertia tensor J about the reference point (the fixed point of a top,
// the centre of mass of a free body), with its inverse and principal frame.
#include <Eigen/Core>

#include "lie/so3.hpp"

namespace lgi::system {

using lie::Mat3;
using lie::Vec3;

struct Inertia {
  Mat3 J = Mat3::Identity();
  Mat3 J_inv = Mat3::Identity();
  /// Principal moments and the rotation P (det +1) with J = P diag(principal) Pᵀ:
  /// body vectors are P · (principal-frame vectors). For a diagonal J the
  /// moments keep the body-axis order (P = I); otherwise they are ascending.
  Vec3 principal = Vec3::Ones();
  Mat3 principal_axes = Mat3::Identity();
  bool diagonal = true;  // J is diagonal in the body axes as given

  Vec3 omega(const Vec3& Pi) const { return J_inv * Pi; }
  Vec3 momentum(const Vec3& Omega) const { return J * Omega; }
};

/// Builds an Inertia from a symmetric positive definite tensor (the scene
/// reader has already checked symmetry and definiteness).
// Out of line (inertia.cpp): the 3×3 eigensolver is instantiated once, not in
// each of the ~200 units that include this header (docs/performance.md §8).
Inertia make_inertia(const Mat3& J);

/// Parallel-axis theorem (docs/conventions.md §5): J = J_c + m(|χ|² I − χ χᵀ).
inline Mat3 parallel_axis(const Mat3& J_cm, double mass, const Vec3& chi) {
  return J_cm + mass * (chi.squaredNorm() * Mat3::Identity() - chi * chi.transpose());
}

}  // namespace lgi::system
