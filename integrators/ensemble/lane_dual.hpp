#pragma once
// Dual numbers with N derivative parts over a lane number T (double or
// Lanes<Batch, K>, lanes.hpp): a + Σ_k b_k ε_k with ε_j ε_k = 0. Evaluating
// f at x + Σ_k v_k ε_k gives f(x) and the N directional derivatives Df(x) v_k
// together, exactly (forward mode; Griewank & Walther, "Evaluating
// Derivatives", 2nd ed., SIAM 2008, ch. 3), the value part once for all N.
// The lane counterpart of integrators/system/dual.hpp (N = 1 there). Every
// operation is a fixed sequence of T operations, so on Lanes each lane is the
// double evaluation bit for bit (docs/ensemble.md, "Cardan tangent flows").
// cos and sin of the value come from lane_sincos.hpp (cos_sin below).
#include <cmath>
#include <cstddef>

#include "integrators/ensemble/lane_sincos.hpp"
#include "integrators/ensemble/lanes.hpp"

namespace lgi::integrators::ensemble {

template <class T, std::size_t N>
struct DualN {
  T a;     // the value
  T b[N];  // the derivatives (the coefficients of ε_k)
};

template <class T, std::size_t N>
inline DualN<T, N> constant_dual(const T& a) {
  DualN<T, N> r;
  r.a = a;
  for (std::size_t k = 0; k < N; ++k) r.b[k] = T(0.0);
  return r;
}

template <class T, std::size_t N>
inline DualN<T, N> operator+(const DualN<T, N>& x, const DualN<T, N>& y) {
  DualN<T, N> r;
  r.a = x.a + y.a;
  for (std::size_t k = 0; k < N; ++k) r.b[k] = x.b[k] + y.b[k];
  return r;
}
template <class T, std::size_t N>
inline DualN<T, N> operator-(const DualN<T, N>& x, const DualN<T, N>& y) {
  DualN<T, N> r;
  r.a = x.a - y.a;
  for (std::size_t k = 0; k < N; ++k) r.b[k] = x.b[k] - y.b[k];
  return r;
}
template <class T, std::size_t N>
inline DualN<T, N> operator-(const DualN<T, N>& x) {
  DualN<T, N> r;
  r.a = -x.a;
  for (std::size_t k = 0; k < N; ++k) r.b[k] = -x.b[k];
  return r;
}
/// (a + bε)(c + dε) = ac + (b c + a d)ε, as integrators/system/dual.hpp.
template <class T, std::size_t N>
inline DualN<T, N> operator*(const DualN<T, N>& x, const DualN<T, N>& y) {
  DualN<T, N> r;
  r.a = x.a * y.a;
  for (std::size_t k = 0; k < N; ++k) r.b[k] = x.b[k] * y.a + x.a * y.b[k];
  return r;
}
/// A constant (of the model) times a dual.
template <class T, std::size_t N>
inline DualN<T, N> operator*(double c, const DualN<T, N>& x) {
  DualN<T, N> r;
  r.a = c * x.a;
  for (std::size_t k = 0; k < N; ++k) r.b[k] = c * x.b[k];
  return r;
}
template <class T, std::size_t N>
inline DualN<T, N> operator+(const DualN<T, N>& x, double c) {
  DualN<T, N> r = x;
  r.a = x.a + c;
  return r;
}
/// 1/(a + bε) = 1/a − (b/a²)ε with r = 1/a: −(b (r r)).
template <class T, std::size_t N>
inline DualN<T, N> reciprocal(const DualN<T, N>& x) {
  DualN<T, N> r;
  r.a = 1.0 / x.a;
  const T rr = r.a * r.a;
  for (std::size_t k = 0; k < N; ++k) r.b[k] = -(x.b[k] * rr);
  return r;
}

/// cos x and sin x of a lane number: lane_sincos.hpp's, the same operations on double and in lanes.
inline void cos_sin(double x, double& c, double& s) { cos_sin_poly(x, c, s); }
template <class B, int K>
inline void cos_sin(const Lanes<B, K>& x, Lanes<B, K>& c, Lanes<B, K>& s) {
  cos_sin_poly(x, c, s);
}

/// cos and sin of a dual: (cos a, −sin a · b) and (sin a, cos a · b).
template <class T, std::size_t N>
inline void cos_sin(const DualN<T, N>& x, DualN<T, N>& c, DualN<T, N>& s) {
  cos_sin(x.a, c.a, s.a);
  for (std::size_t k = 0; k < N; ++k) {
    c.b[k] = -(s.a * x.b[k]);
    s.b[k] = c.a * x.b[k];
  }
}

}  // namespace lgi::integrators::ensemble
