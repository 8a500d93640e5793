#pragma once
// The inertia tensor J about the reference point (the fixed point of a top,
// the centre of mass of a free body), with its inverse and principal frame.
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

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
inline Inertia make_inertia(const Mat3& J) {
  Inertia in;
  in.J = 0.5 * (J + J.transpose());
  in.J_inv = in.J.inverse();
  in.diagonal = in.J(0, 1) == 0.0 && in.J(0, 2) == 0.0 && in.J(1, 2) == 0.0;
  if (in.diagonal) {
    in.principal = in.J.diagonal();
    in.principal_axes = Mat3::Identity();
  } else {
    Eigen::SelfAdjointEigenSolver<Mat3> eig(in.J);
    in.principal = eig.eigenvalues();
    in.principal_axes = eig.eigenvectors();
    if (in.principal_axes.determinant() < 0.0) in.principal_axes.col(2) *= -1.0;
  }
  return in;
}

/// Parallel-axis theorem (docs/conventions.md §5): J = J_c + m(|χ|² I − χ χᵀ).
inline Mat3 parallel_axis(const Mat3& J_cm, double mass, const Vec3& chi) {
  return J_cm + mass * (chi.squaredNorm() * Mat3::Identity() - chi * chi.transpose());
}

}  // namespace lgi::system
