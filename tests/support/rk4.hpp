#pragma once
// The classical RK4 with a fixed step, knowing nothing about exp, log or
// their derivatives: the independent reference of the lie/ tests that
// integrate a chart's kinematics, with the time-dependent body angular
// velocity they drive it with.
#include <cmath>
#include <functional>

#include "lie/so3.hpp"

namespace lgi::testing {

/// RK4 over [0, T] in n steps for ẋ = f(t, x); V a fixed-size Eigen vector or matrix.
template <class V>
V rk4(const std::function<V(double, const V&)>& f, V x, double T, int n) {
  const double h = T / n;
  for (int i = 0; i < n; ++i) {
    const double t = i * h;
    const V k1 = f(t, x);
    const V k2 = f(t + 0.5 * h, V(x + 0.5 * h * k1));
    const V k3 = f(t + 0.5 * h, V(x + 0.5 * h * k2));
    const V k4 = f(t + h, V(x + h * k3));
    x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return x;
}

/// A body angular velocity whose values at different times do not commute.
inline lie::Vec3 omega_of_t(double t) {
  return lie::Vec3(1.0 + 0.5 * std::sin(3.0 * t), -0.7 * std::cos(2.0 * t), 0.4 + t);
}

/// Ṙ = R Ω̂(t) from R0 over [0, T] by RK4 in ℝ⁹.
inline lie::Mat3 body_attitude_rk4(const lie::Mat3& R0, double T, int n) {
  return rk4<lie::Mat3>([](double t, const lie::Mat3& R) { return lie::Mat3(R * lie::hat(omega_of_t(t))); }, R0, T, n);
}

}  // namespace lgi::testing
