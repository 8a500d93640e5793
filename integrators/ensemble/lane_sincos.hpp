#pragma once
// cos x and sin x written once for a lane number T (double or Lanes<Batch, K>,
// lanes.hpp) from +, −, × and select, so that every lane is the double
// evaluation bit for bit without a libm call per lane (docs/ensemble.md,
// "Cardan tangent flows"). Not libm's bits: the Cardan kernel uses it on
// double too.
//   Reduction (Cody & Waite; the three 33-bit pieces of π/2 of fdlibm's
//   e_rem_pio2.c): n = round(x · 2/π) by adding and subtracting 1.5 · 2⁵²,
//   y = ((x − n P1) − n P2) − n P3, with n P1 and n P2 exact for |n| < 2²⁰ and
//   x − n P1 exact (Sterbenz); |y| ≤ π/4 + 1e-15, absolute error about 1e-16.
//   Kernels on [−π/4, π/4]: fdlibm's k_sin.c and k_cos.c polynomials (Sun
//   Microsystems 1993; degree 13 and 14, relative error below 2⁻⁵⁸), the tail of
//   y taken as 0.
//   Quadrant j = n mod 4 (exact in doubles): (sin, cos) = (s, c), (c, −s), (−s, −c), (−c, s).
// |x| > 1.5e6 (and NaN, ±∞): libm's, lane by lane, on double alike.
// Accuracy: |error| ≤ 3e-16 + |x| · 2⁻⁷⁵ absolute against libm
// (tests/test_ensemble_cardan.cpp); near a zero of sin or cos the relative
// error is larger than libm's (the reduction is absolute), which the
// dynamics do not see.
#include <cmath>

#include "integrators/ensemble/lanes.hpp"

namespace lgi::integrators::ensemble {

inline bool equal(double x, double c) { return x == c; }
inline bool less_equal(double x, double c) { return x <= c; }
inline double magnitude(double x) { return std::abs(x); }
template <class B, int K>
inline Lanes<B, K> magnitude(const Lanes<B, K>& x) {
  return abs(x);
}

namespace sincos_detail {

inline constexpr double two_over_pi = 6.36619772367581382433e-01;
inline constexpr double pio2_1 = 1.57079632673412561417e+00;  // the first 33 bits of π/2
inline constexpr double pio2_2 = 6.07710050630396597660e-11;  // the next 33
inline constexpr double pio2_3 = 2.02226624871116645580e-21;  // the rest
inline constexpr double round_magic = 6755399441055744.0;     // 1.5 · 2⁵²: x + it − it rounds x to an integer
inline constexpr double limit = 1.5e6;                        // |n| < 2²⁰ below it
inline constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                        S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                        S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
inline constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                        C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                        C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;

/// libm's cos and sin where `small` is false (|x| > limit, or not finite), as cos_sin_unless.
inline void large(bool small, double x, double& c, double& s) {
  if (!small) c = std::cos(x), s = std::sin(x);
}
template <class B, int K>
inline void large(const LaneMask<B, K>& small, const Lanes<B, K>& x, Lanes<B, K>& c, Lanes<B, K>& s) {
  if (all(small)) return;
  Lanes<B, K> lc, ls;
  cos_sin_unless(small, x, lc, ls);
  c = select(small, c, lc);
  s = select(small, s, ls);
}

}  // namespace sincos_detail

/// c = cos x, s = sin x (top of this file).
template <class T>
inline void cos_sin_poly(const T& x, T& c, T& s) {
  using namespace sincos_detail;
  const T n = (x * two_over_pi + round_magic) - round_magic;
  const T y = ((x - n * pio2_1) - n * pio2_2) - n * pio2_3;
  const T q = n * 0.25;
  T f = (q + round_magic) - round_magic;
  f = select(less(q, f), f - 1.0, f);  // floor(n / 4)
  const T j = n - 4.0 * f;             // n mod 4, exactly
  const T z = y * y;
  const T ks = y + (z * y) * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
  const T r = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
  const T hz = 0.5 * z;
  const T w = 1.0 - hz;
  const T kc = w + (((1.0 - w) - hz) + z * r);
  const auto odd = equal(j, 1.0) | equal(j, 3.0);
  const T sin_part = select(odd, kc, ks), cos_part = select(odd, ks, kc);
  s = select(less(j, 1.5), sin_part, -sin_part);                              // j = 2, 3: −
  c = select(equal(j, 1.0) | equal(j, 2.0), -cos_part, cos_part);              // j = 1, 2: −
  large(less_equal(magnitude(x), limit), x, c, s);
}

}  // namespace lgi::integrators::ensemble
