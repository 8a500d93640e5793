#pragma once
// Forward-mode automatic differentiation: a dual number v + d ε (ε² = 0),
// nestable (Dual<Dual<double>> gives second derivatives). Only what the
// Cardan-model check needs (tests/test_cardan_model.cpp): + − × and sin, cos.
#include <cmath>
#include <cstddef>

namespace lgi::testing {

template <class T>
struct Dual {
  T v{};
  T d{};
  Dual() = default;
  Dual(double x) : v(x), d(0.0) {}  // NOLINT: constants lift implicitly
  Dual(T value, T derivative) : v(value), d(derivative) {}
};

template <class T> Dual<T> operator+(const Dual<T>& a, const Dual<T>& b) { return {a.v + b.v, a.d + b.d}; }
template <class T> Dual<T> operator-(const Dual<T>& a, const Dual<T>& b) { return {a.v - b.v, a.d - b.d}; }
template <class T> Dual<T> operator-(const Dual<T>& a) { return {-a.v, -a.d}; }
template <class T> Dual<T> operator*(const Dual<T>& a, const Dual<T>& b) { return {a.v * b.v, a.d * b.v + a.v * b.d}; }
template <class T> Dual<T> operator*(double a, const Dual<T>& b) { return {a * b.v, a * b.d}; }
template <class T> Dual<T> sin(const Dual<T>& a) {
  using std::cos;
  using std::sin;
  return {sin(a.v), cos(a.v) * a.d};
}
template <class T> Dual<T> cos(const Dual<T>& a) {
  using std::cos;
  using std::sin;
  return {cos(a.v), -1.0 * (sin(a.v) * a.d)};
}

/// A fixed array indexed by int (the loops below count with int).
template <class T, std::size_t N>
struct Arr {
  T v[N];
  T& operator[](int i) { return v[i]; }
  const T& operator[](int i) const { return v[i]; }
};
template <class S> using Mat3S = Arr<Arr<S, 3>, 3>;
template <class S> using Vec3S = Arr<S, 3>;

template <class S> Mat3S<S> mul(const Mat3S<S>& a, const Mat3S<S>& b) {
  Mat3S<S> c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      S sum(0.0);
      for (int k = 0; k < 3; ++k) sum = sum + a[i][k] * b[k][j];
      c[i][j] = sum;
    }
  return c;
}
template <class S> Vec3S<S> mul(const Mat3S<S>& a, const Vec3S<S>& x) {
  Vec3S<S> y{};
  for (int i = 0; i < 3; ++i) y[i] = a[i][0] * x[0] + a[i][1] * x[1] + a[i][2] * x[2];
  return y;
}
/// Elementary rotations about e1, e2, e3 (axis 0, 1, 2) by a.
template <class S> Mat3S<S> rotation(int axis, const S& a) {
  using std::cos;
  using std::sin;
  const S c = cos(a), s = sin(a), o(0.0), l(1.0);
  if (axis == 0) return {{{l, o, o}, {o, c, -s}, {o, s, c}}};
  if (axis == 1) return {{{c, o, s}, {o, l, o}, {-s, o, c}}};
  return {{{c, -s, o}, {s, c, o}, {o, o, l}}};
}

}  // namespace lgi::testing
