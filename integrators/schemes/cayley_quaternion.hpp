#pragma once
// The attitude of a free body's preprocessed DMV run kept as a unit
// quaternion q, scalar first (lie/quaternion.hpp), instead of as R
// (moser_veselov.hpp, DmvPreprocessed; docs/performance.md §3, "The
// attitude as a quaternion").
//
// A DMV step is R ← R F with F = cay(2f) = I + 2/(1 + |f|²)(f̂ + f̂²), the
// rotation by 2 atan|f| about f/|f|, whose unit quaternion is
//   p = (1, f)/s,   s = √(1 + |f|²)
// (R(p) = I + 2 p_w p̂_v + 2 p̂_v² = F). As R(a ⊗ b) = R(a) R(b) for the
// Hamilton product, the step is q ← q ⊗ p, applied as a compensated increment
// like R's (compensated_sum.hpp):
//   q ← q + q ⊗ (e, v),   e = 1/s − 1 = −|f|²/((1 + |f|²) + s),   v = (1 + e) f,
// e formed without the cancellation of 1/s − 1, so the increment is accurate
// to ε relative and the sum carries its rounding error, as the other
// updates of the step do. This is 16 products and 16 sums, a square root and
// a division, against 27 products, 18 sums and 9 compensated sums for R F;
// R(q) is formed only where the run reads R (stepper_loop.hpp, "Kept
// attitude"). No renormalisation: |q| is 1 to round-off, as RᵀR = I was.
// Two roundings of the step leave |p| ≠ 1 by about ε: those of 1 + |f|²
// and of s, random from step to step, so |q| − 1 walks like √n ε, as the
// orthogonality of the R form did (tests/test_kept_attitude.cpp).
#include "integrators/schemes/cayley_quaternion_increment.hpp"
#include "integrators/core/compensated_sum.hpp"
#include "integrators/core/scheme_interface.hpp"
#include "lie/quaternion.hpp"

namespace lgi::integrators::moser_veselov {

/// A run's attitude as a unit quaternion with the carry of its compensated sum.
struct CayleyQuaternion {
  double q[4] = {1.0, 0.0, 0.0, 0.0};
  double carry[4] = {0.0, 0.0, 0.0, 0.0};
  /// q from R (Shepperd's method, lie::quat_from_matrix), no carry.
  void set_from(const Mat3& R) {
    const Eigen::Quaterniond p = lie::quat_from_matrix(R);
    q[0] = p.w(), q[1] = p.x(), q[2] = p.y(), q[3] = p.z();
    for (double& c : carry) c = 0.0;
  }
  /// R ← R(q) (lie::rotation_entries).
  void write(Mat3& R) const {
    double e[9];
    lie::rotation_entries(q[0], q[1], q[2], q[3], e);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) R(i, j) = e[3 * i + j];
  }
  /// q ← q ⊗ p for F = cay(2f), ff = |f|² (header comment).
  void rotate(const double (&f)[3], double ff) {
    double dq[4];
    cayley_quaternion_increment(q, f, ff, dq);
    for (int i = 0; i < 4; ++i) add_compensated(q[i], dq[i], carry[i]);
  }
};

}  // namespace lgi::integrators::moser_veselov
