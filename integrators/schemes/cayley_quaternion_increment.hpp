#pragma once
// The increment of a quaternion attitude over one DMV step (cayley_quaternion.hpp
// states the update), for doubles and the ensemble's lanes alike: no Eigen
// here, as the lane kernels share no inline code with the rest of lgi
// (integrators/ensemble/ensemble_model.hpp).
#include <cmath>

namespace lgi::integrators::moser_veselov {

/// dq = q ⊗ p − q for the unit quaternion p of cay(2f), ff = |f|² as the
/// step rounded it ((f₀² + f₁²) + f₂²): dq = q ⊗ (e, v), e = 1/s − 1, v = (1 + e) f.
template <class T>
inline void cayley_quaternion_increment(const T (&q)[4], const T (&f)[3], const T& ff, T (&dq)[4]) {
  using std::sqrt;
  const T s = sqrt(1.0 + ff);
  const T e = -ff / ((1.0 + ff) + s);
  const T r = 1.0 + e;  // 1/s
  const T v0 = r * f[0], v1 = r * f[1], v2 = r * f[2];
  dq[0] = q[0] * e - ((q[1] * v0 + q[2] * v1) + q[3] * v2);
  dq[1] = (q[0] * v0 + e * q[1]) + (q[2] * v2 - q[3] * v1);
  dq[2] = (q[0] * v1 + e * q[2]) + (q[3] * v0 - q[1] * v2);
  dq[3] = (q[0] * v2 + e * q[3]) + (q[1] * v1 - q[2] * v0);
}

}  // namespace lgi::integrators::moser_veselov
