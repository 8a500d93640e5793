#pragma once
// The SO(3) algebra of lie/so3.hpp for lane numbers (lanes.hpp): 3-vectors,
// 3×3 matrices, hat, exp and dexp⁻¹, operation for operation as the scalar
// code evaluates them, so that each lane's bits are the scalar result
// (docs/ensemble.md; tests/test_ensemble.cpp checks every function here and
// whole runs against the scalar schemes).
//
// "As the scalar code evaluates them" includes Eigen's own order for the
// fixed-size products of the scalar code (Eigen 3.4, SSE2, no FMA):
//  - sums of three products in dot(), squaredNorm() and Aᵀv:   (x0 + x1) + x2;
//  - A·v and A·B (3×3): rows 0 and 1 come from a two-lane packet, (x0 + x1) + x2,
//    row 2 from the scalar reduction, x0 + (x1 + x2).
// Zeros are not skipped (0·x is −0 or NaN for some x, and −0 + 0 = +0).
#include <cmath>

#include "integrators/ensemble/lanes.hpp"

namespace lgi::integrators::ensemble {

template <class T>
struct V3 {
  T v[3];
};
template <class T>
struct M3 {
  T m[3][3];  // m[row][column]
};

template <class T>
inline V3<T> zero3() {
  return {{T(0.0), T(0.0), T(0.0)}};
}
template <class T>
inline V3<T> add(const V3<T>& a, const V3<T>& b) {
  return {{a.v[0] + b.v[0], a.v[1] + b.v[1], a.v[2] + b.v[2]}};
}
/// c·a (a scalar times a vector: c·a_i for each i).
template <class T, class C>
inline V3<T> scale(const C& c, const V3<T>& a) {
  return {{c * a.v[0], c * a.v[1], c * a.v[2]}};
}
/// a × b as Eigen's cross(): (a1 b2 − a2 b1, a2 b0 − a0 b2, a0 b1 − a1 b0).
template <class T, class U>
inline V3<T> cross(const V3<T>& a, const V3<U>& b) {
  return {{a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2], a.v[0] * b.v[1] - a.v[1] * b.v[0]}};
}
template <class T>
inline T squared_norm(const V3<T>& a) {
  return (a.v[0] * a.v[0] + a.v[1] * a.v[1]) + a.v[2] * a.v[2];
}
/// Sums of three products in Eigen's order for rows 0, 1 and for row 2 of a 3×3 product.
template <class T>
inline T sum_packet(const T& x0, const T& x1, const T& x2) {
  return (x0 + x1) + x2;
}
template <class T>
inline T sum_scalar(const T& x0, const T& x1, const T& x2) {
  return x0 + (x1 + x2);
}
/// A·v for a matrix A common to all lanes (J⁻¹).
template <class T>
inline V3<T> mat_vec(const double (&A)[3][3], const V3<T>& x) {
  auto p = [&](int i, int k) { return A[i][k] * x.v[k]; };
  return {{sum_packet(p(0, 0), p(0, 1), p(0, 2)), sum_packet(p(1, 0), p(1, 1), p(1, 2)),
           sum_scalar(p(2, 0), p(2, 1), p(2, 2))}};
}
/// Aᵀv for a lane matrix A and a vector common to all lanes (Rᵀ B).
template <class T>
inline V3<T> transposed_mat_vec(const M3<T>& A, const double (&x)[3]) {
  auto p = [&](int k, int i) { return A.m[k][i] * x[k]; };
  return {{sum_packet(p(0, 0), p(1, 0), p(2, 0)), sum_packet(p(0, 1), p(1, 1), p(2, 1)),
           sum_packet(p(0, 2), p(1, 2), p(2, 2))}};
}
/// A·B.
template <class T>
inline M3<T> mat_mat(const M3<T>& A, const M3<T>& B) {
  M3<T> r;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 2; ++i)
      r.m[i][j] = sum_packet(A.m[i][0] * B.m[0][j], A.m[i][1] * B.m[1][j], A.m[i][2] * B.m[2][j]);
    r.m[2][j] = sum_scalar(A.m[2][0] * B.m[0][j], A.m[2][1] * B.m[1][j], A.m[2][2] * B.m[2][j]);
  }
  return r;
}

/// Row 2 of A·B, as mat_mat computes it; rows 0 and 1 are left unset.
template <class T>
inline M3<T> last_row_product(const M3<T>& A, const M3<T>& B) {
  M3<T> r;
  for (int j = 0; j < 3; ++j)
    r.m[2][j] = sum_scalar(A.m[2][0] * B.m[0][j], A.m[2][1] * B.m[1][j], A.m[2][2] * B.m[2][j]);
  return r;
}

/// exp(ξ̂) = I + a ξ̂ + b ξ̂² (lie::exp_so3: the same coefficients, the same
/// series below θ = 1e-4, sin from libm lane by lane).
template <class T>
inline M3<T> exp_so3(const V3<T>& xi) {
  const T theta2 = squared_norm(xi);
  const T theta = sqrt(theta2);
  const auto series = less(theta, 1e-4);
  // Each side only where some lane takes it (the scalar code computes one).
  auto series_a = [&] { return 1.0 - theta2 / 6.0 + theta2 * theta2 / 120.0; };
  auto series_b = [&] { return 0.5 - theta2 / 24.0 + theta2 * theta2 / 720.0; };
  T a, b;
  if (all(series)) {
    a = series_a();
    b = series_b();
  } else {
    T sin_theta, sin_half;
    sin_sin_unless(series, theta, sin_theta, sin_half);
    a = sin_theta / theta;
    const T s = sin_half / theta;
    b = 2.0 * s * s;
    if (any(series)) {
      a = select(series, series_a(), a);
      b = select(series, series_b(), b);
    }
  }
  const T zero(0.0), one(1.0);
  const M3<T> X{{{zero, -xi.v[2], xi.v[1]}, {xi.v[2], zero, -xi.v[0]}, {-xi.v[1], xi.v[0], zero}}};
  M3<T> bX;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) bX.m[i][j] = b * X.m[i][j];
  M3<T> r = mat_mat(bX, X);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = ((i == j ? one : zero) + a * X.m[i][j]) + r.m[i][j];
  return r;
}

/// c(θ) = (1 − (θ/2) cot(θ/2))/θ² (lie::detail::dexpinv_coefficient).
template <class T>
inline T dexpinv_coefficient(const T& theta2) {
  const T theta = sqrt(theta2);
  const auto series = less(theta, 1e-2);
  const T c = 1.0 / 12.0 + theta2 / 720.0 + theta2 * theta2 / 30240.0;
  if (all(series)) return c;
  const T half = 0.5 * theta;
  T cos_half, sin_half;
  cos_sin_unless(series, half, cos_half, sin_half);
  return select(series, c, (1.0 - half * cos_half / sin_half) / theta2);
}

/// dexp⁻¹_body(ξ) Ω = Ω + ½ ξ × Ω + c(θ) ξ × (ξ × Ω) (lie::dexpinv_body).
template <class T>
inline V3<T> dexpinv_body(const V3<T>& xi, const V3<T>& omega) {
  const V3<T> xo = cross(xi, omega);
  const T c = dexpinv_coefficient(squared_norm(xi));
  const V3<T> xxo = cross(xi, xo);
  V3<T> r;
  for (int i = 0; i < 3; ++i) r.v[i] = omega.v[i] + 0.5 * xo.v[i] + c * xxo.v[i];
  return r;
}

}  // namespace lgi::integrators::ensemble
