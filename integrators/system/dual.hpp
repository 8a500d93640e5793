#pragma once
// Dual numbers a + b·ε, ε² = 0, for forward-mode differentiation: evaluating
// f at x + v·ε gives f(x) + (Df(x) v)·ε exactly, with no step size and no
// truncation error (Griewank & Walther, "Evaluating Derivatives", 2nd ed.,
// SIAM 2008, ch. 3). Only the operations the Cardan field needs
// (integrators/system/cardan_field.hpp) are defined: +, −, ×, ÷, sin, cos.
// A plain pair of doubles, so Eigen matrices of Dual are allocation-free.
#include <cmath>

#include <Eigen/Core>

namespace lgi::system {

struct Dual {
  double a = 0.0;  // the value
  double b = 0.0;  // the derivative (the coefficient of ε)

  constexpr Dual() = default;
  constexpr Dual(double value) : a(value) {}  // NOLINT: implicit, as for a scalar literal
  constexpr Dual(double value, double derivative) : a(value), b(derivative) {}

  constexpr Dual& operator+=(const Dual& y) {
    a += y.a;
    b += y.b;
    return *this;
  }
  constexpr Dual& operator-=(const Dual& y) {
    a -= y.a;
    b -= y.b;
    return *this;
  }
  constexpr Dual& operator*=(const Dual& y) {
    b = b * y.a + a * y.b;
    a *= y.a;
    return *this;
  }
  constexpr Dual& operator/=(const Dual& y) {
    // (a + bε)/(c + dε) = a/c + (b c − a d)/c² ε
    b = (b * y.a - a * y.b) / (y.a * y.a);
    a /= y.a;
    return *this;
  }
};

constexpr Dual operator+(Dual x, const Dual& y) { return x += y; }
constexpr Dual operator-(Dual x, const Dual& y) { return x -= y; }
constexpr Dual operator*(Dual x, const Dual& y) { return x *= y; }
constexpr Dual operator/(Dual x, const Dual& y) { return x /= y; }
constexpr Dual operator-(const Dual& x) { return {-x.a, -x.b}; }
constexpr Dual operator+(const Dual& x) { return x; }
// Comparisons look at the value only (Eigen's generic code may branch on them).
constexpr bool operator==(const Dual& x, const Dual& y) { return x.a == y.a && x.b == y.b; }
constexpr bool operator!=(const Dual& x, const Dual& y) { return !(x == y); }
constexpr bool operator<(const Dual& x, const Dual& y) { return x.a < y.a; }
constexpr bool operator>(const Dual& x, const Dual& y) { return x.a > y.a; }
constexpr bool operator<=(const Dual& x, const Dual& y) { return x.a <= y.a; }
constexpr bool operator>=(const Dual& x, const Dual& y) { return x.a >= y.a; }

inline Dual sin(const Dual& x) { return {std::sin(x.a), std::cos(x.a) * x.b}; }
inline Dual cos(const Dual& x) { return {std::cos(x.a), -std::sin(x.a) * x.b}; }

}  // namespace lgi::system

namespace Eigen {
template <>
struct NumTraits<lgi::system::Dual> : NumTraits<double> {
  using Real = lgi::system::Dual;
  using NonInteger = lgi::system::Dual;
  using Literal = lgi::system::Dual;
  using Nested = lgi::system::Dual;
  enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 1, ReadCost = 2, AddCost = 2, MulCost = 3 };
};
}  // namespace Eigen
