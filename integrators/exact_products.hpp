#pragma once
// Dekker's error-free product (Dekker, Numer. Math. 18 (1971) 224–242, §5:
// Veltkamp's split and "mul12"): for p = fl(x y), x y − p is a double and is
// computed exactly from the halves of x and y. Templates on the number type,
// so the scalar DMV (moser_veselov_diagonal.hpp) and its ensemble kernel
// (ensemble/dmv_kernel.hpp, compiled once per instruction set, which must not
// include Eigen) share one source and round alike. Needs IEEE arithmetic as
// written: no -ffast-math, and -ffp-contract=off (cmake/warnings.cmake).
namespace lgi::integrators {

/// Veltkamp's split x = hi + lo, each with at most 26 significant bits.
template <class T>
inline void veltkamp_split(const T& x, T& hi, T& lo) {
  const T c = 134217729.0 * x;  // 2^27 + 1
  hi = c - (c - x);
  lo = x - hi;
}

/// x y − p exactly for p = fl(x y), x given split.
template <class T>
inline T product_error(const T& x_hi, const T& x_lo, const T& y, const T& p) {
  T y_hi, y_lo;
  veltkamp_split(y, y_hi, y_lo);
  return ((x_hi * y_hi - p) + x_hi * y_lo + x_lo * y_hi) + x_lo * y_lo;
}

}  // namespace lgi::integrators
