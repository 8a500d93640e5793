// make_inertia (inertia.hpp), in its own unit.
#include "integrators/system/inertia.hpp"

#include <Eigen/Eigenvalues>

namespace lgi::system {

Inertia make_inertia(const Mat3& J) {
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

}  // namespace lgi::system
