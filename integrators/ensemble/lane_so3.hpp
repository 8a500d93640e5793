#pragma once
// The SO(3) algebra of the RKMK schemes for lane numbers (lanes.hpp):
// 3-vectors, 3×3 matrices, exp and dexp⁻¹, operation for operation as the
// scalar code evaluates them, so that each lane's bits are the scalar result
// (docs/ensemble.md; tests/test_ensemble.cpp checks every function here and
// whole runs against the scalar schemes).
//
// exp and dexp⁻¹ are lie/exp_series.hpp's, the very source rkmk.hpp
// evaluates. "As the scalar code evaluates them" also includes Eigen's own
// order for the fixed-size products left in the scalar code (Eigen 3.4,
// SSE2, no FMA):
//  - sums of three products in dot(), squaredNorm() and Aᵀv:   (x0 + x1) + x2;
//  - A·v (3×3): rows 0 and 1 come from a two-lane packet, (x0 + x1) + x2,
//    row 2 from the scalar reduction, x0 + (x1 + x2).
// Zeros are not skipped (0·x is −0 or NaN for some x, and −0 + 0 = +0).
#include <cmath>

#include "integrators/ensemble/lanes.hpp"
#include "lie/exp_series.hpp"

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
/// The coefficients a, b, c of exp and dexp⁻¹ (lie/exp_series.hpp) in every
/// lane, as rkmk_pair_detail::map_coefficients computes them: the short
/// series where θ² < 1/4, the series where θ² < 1, else the closed forms from
/// libm's sin and cos of θ/2, lane by lane; each side computed only where
/// some lane takes it. a and b only when `with_attitude` (a free body never
/// forms a stage attitude).
template <class T>
struct Coefficients {
  T a, b, c;
};
/// In each lane, x's coefficients where `take_x`, else y's (a and b only with the attitude).
template <class T, class Mask>
inline Coefficients<T> select_coefficients(const Mask& take_x, const Coefficients<T>& x, Coefficients<T> y,
                                           bool with_attitude) {
  y.c = select(take_x, x.c, y.c);
  if (with_attitude) {
    y.a = select(take_x, x.a, y.a);
    y.b = select(take_x, x.b, y.b);
  }
  return y;
}
/// The series side: the short series where θ² < 1/4, the full ones elsewhere.
template <class T, class Mask>
inline Coefficients<T> series_coefficients(const T& t2, const Mask& in_short, bool with_attitude) {
  namespace ex = lie::exp_series;
  Coefficients<T> out{T(0.0), T(0.0), T(0.0)};
  const bool some_short = any(in_short);
  if (some_short) {
    out.c = ex::series_c<true>(t2);
    if (with_attitude) {
      out.a = ex::series_a<true>(t2);
      out.b = ex::series_b<true>(t2);
    }
    if (all(in_short)) return out;
  }
  const Coefficients<T> full{ex::series_a(t2), ex::series_b(t2), ex::series_c(t2)};
  if (!some_short) return full;
  return select_coefficients(in_short, out, full, with_attitude);
}
template <class T>
inline Coefficients<T> map_coefficients(const T& t2, bool with_attitude) {
  namespace ex = lie::exp_series;
  const auto in_series = less(t2, ex::series_bound);
  Coefficients<T> series{T(0.0), T(0.0), T(0.0)};
  const bool some_series = any(in_series);
  if (some_series) {
    series = series_coefficients(t2, less(t2, ex::short_series_bound), with_attitude);
    if (all(in_series)) return series;
  }
  const T theta = sqrt(t2);
  const T half = 0.5 * theta;
  T k, s;
  cos_sin_unless(in_series, half, k, s);
  Coefficients<T> closed{T(0.0), T(0.0), T(0.0)};
  closed.c = ex::closed_c(t2, theta, s, k);
  if (with_attitude) {
    closed.a = ex::closed_a(theta, s, k);
    closed.b = ex::closed_b(theta, s);
  }
  if (!some_series) return closed;
  return select_coefficients(in_series, series, closed, with_attitude);
}

/// Row i of R exp(ŵ) into out (lie::exp_series::times_exp_row).
template <class T>
inline void times_exp_row(const M3<T>& R, int i, const V3<T>& w, const Coefficients<T>& m, M3<T>& out) {
  lie::exp_series::times_exp_row(R.m[i], w.v, m.a, m.b, out.m[i]);
}
/// R exp(ŵ).
template <class T>
inline M3<T> times_exp(const M3<T>& R, const V3<T>& w, const Coefficients<T>& m) {
  M3<T> out;
  for (int i = 0; i < 3; ++i) times_exp_row(R, i, w, m, out);
  return out;
}

/// dexp⁻¹_body(w) Ω (lie::exp_series::dexpinv).
template <class T>
inline V3<T> dexpinv_body(const V3<T>& w, const V3<T>& omega, const Coefficients<T>& m) {
  V3<T> out;
  lie::exp_series::dexpinv(w.v, omega.v, m.c, out.v);
  return out;
}

}  // namespace lgi::integrators::ensemble
