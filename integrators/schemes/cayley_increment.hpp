#pragma once
// F − I = c N for the Cayley step F = cay(2f) of the DMV schemes
// (moser_veselov.hpp): N = f̂ + f̂² (row-major), f̂² = f fᵀ − |f|² I,
// c = 2/(1 + |f|²), and the increment of Π ← Fᵀ Π. For doubles and the
// ensemble's lanes alike (integrators/ensemble/dmv_kernel.hpp): no Eigen here,
// as the lane kernels share no inline code with the rest of lgi
// (integrators/ensemble/ensemble_model.hpp).
namespace lgi::integrators::moser_veselov {

template <class T>
struct CayleyIncrement {
  T N[9], c, ff;  // ff = |f|² = (f₀² + f₁²) + f₂²
  explicit CayleyIncrement(const T (&f)[3]) {
    const T x = f[0], y = f[1], z = f[2];
    const T xx = x * x, yy = y * y, zz = z * z;
    ff = (xx + yy) + zz;
    c = 2.0 / (1.0 + ff);
    const T xy = x * y, xz = x * z, yz = y * z;
    const T n[9] = {-(yy + zz), xy - z, xz + y, xy + z, -(xx + zz), yz - x, xz - y, yz + x, -(xx + yy)};
    for (int k = 0; k < 9; ++k) N[k] = n[k];
  }
  /// c Nᵀ Π, c last: the increment of Π ← Fᵀ Π.
  void momentum_increment(const T (&P)[3], T (&dP)[3]) const {
    for (int j = 0; j < 3; ++j) dP[j] = c * ((N[j] * P[0] + N[3 + j] * P[1]) + N[6 + j] * P[2]);
  }
};

}  // namespace lgi::integrators::moser_veselov
