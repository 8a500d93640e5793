#pragma once
// The error measure of the controlled baselines, and how odeint is told to
// use it.
//
// odeint's default_error_checker scales each component by
// eps_abs + eps_rel (|x_i| + |dt| |ẋ_i|). For these states that is not a
// sensible relative error: the unwrapped Euler angles ψ, φ grow without
// bound (φ ≈ 500 rad after 10 s of a 50 rad/s spin), so a componentwise
// relative tolerance would let their error grow in proportion, and a
// component of Ω that crosses zero gets no relative allowance at all. With
// --tol TOL the baselines use abs = rel = TOL and
//   attitude coordinates (angles in rad, rotation vector, quaternion and
//   matrix entries: all of order one):       sc_i = TOL              (absolute)
//   angular velocity Ω (one block):           sc_i = TOL (1 + |Ω| + |dt| |Ω̇|)
// with |·| the Euclidean norm of the block at the start of the step (odeint's
// own weights a_x = a_dxdt = 1, applied to the block instead of the
// component), and accept a step when max_i |err_i| / sc_i ≤ 1 (odeint's max
// norm). This matches rkmk-dp54 (integrators/schemes/rkmk_adaptive.hpp): attitude
// error absolute in radians, momentum error relative.
//
// odeint's controlled_runge_kutta and bulirsch_stoer build their checker as
// default_error_checker<Value, Algebra, Operations>; the baselines run them
// with the algebra BaselineAlgebra<Coords> (odeint's array_algebra under a
// name of our own), and the partial specialisation below supplies the
// measure above for exactly those steppers. rosenbrock4's controller has its
// own, fixed, measure; the stepper wrappers (odeint_steppers.hpp) replaces it by
// weighted_error() too.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <boost/numeric/odeint/algebra/array_algebra.hpp>
#include <boost/numeric/odeint/algebra/default_operations.hpp>
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>

namespace lgi::integrators::baselines {

/// odeint's array_algebra, under a name that selects our error checker.
template <class Coords>
struct BaselineAlgebra : boost::numeric::odeint::array_algebra {};

/// |Ω| + |dt| |Ω̇| for the Ω block of a state and its derivative.
template <class Coords, class State, class Deriv>
double omega_block_scale(const State& x, const Deriv& dxdt, double dt, double a_x = 1.0, double a_dxdt = 1.0) {
  double w2 = 0.0, d2 = 0.0;
  for (std::size_t i = Coords::omega_offset; i < Coords::size; ++i) {
    w2 += x[i] * x[i];
    d2 += dxdt[i] * dxdt[i];
  }
  return a_x * std::sqrt(w2) + a_dxdt * std::abs(dt) * std::sqrt(d2);
}

/// max_i |err_i| / sc_i with the scales above; omega_scale is |Ω| (+ |dt||Ω̇|).
template <class Coords, class Err>
double weighted_error(const Err& err, double omega_scale, double eps_abs, double eps_rel) {
  double e = 0.0;
  for (std::size_t i = 0; i < Coords::omega_offset; ++i) e = std::max(e, std::abs(err[i]) / eps_abs);
  const double sc = eps_abs + eps_rel * omega_scale;
  for (std::size_t i = Coords::omega_offset; i < Coords::size; ++i) e = std::max(e, std::abs(err[i]) / sc);
  // A non-finite error estimate (a stage evaluated at a singular point) must
  // reject the step: odeint accepts unless error > 1, and NaN > 1 is false.
  return std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
}

}  // namespace lgi::integrators::baselines

namespace boost::numeric::odeint {

/// The baselines' error measure for controlled_runge_kutta and bulirsch_stoer
/// (see the top of this file). Same constructor and interface as odeint's.
template <class Coords>
class default_error_checker<double, lgi::integrators::baselines::BaselineAlgebra<Coords>, default_operations> {
 public:
  using value_type = double;
  using algebra_type = lgi::integrators::baselines::BaselineAlgebra<Coords>;
  using operations_type = default_operations;

  default_error_checker(double eps_abs = 1.0e-6, double eps_rel = 1.0e-6, double a_x = 1.0, double a_dxdt = 1.0)
      : eps_abs_(eps_abs), eps_rel_(eps_rel), a_x_(a_x), a_dxdt_(a_dxdt) {}

  template <class State, class Deriv, class Err, class Time>
  double error(const State& x_old, const Deriv& dxdt_old, Err& x_err, Time dt) const {
    const double scale =
        lgi::integrators::baselines::omega_block_scale<Coords>(x_old, dxdt_old, static_cast<double>(dt), a_x_, a_dxdt_);
    return lgi::integrators::baselines::weighted_error<Coords>(x_err, scale, eps_abs_, eps_rel_);
  }
  template <class State, class Deriv, class Err, class Time>
  double error(algebra_type& /*algebra*/, const State& x_old, const Deriv& dxdt_old, Err& x_err, Time dt) const {
    return error(x_old, dxdt_old, x_err, dt);
  }

 private:
  double eps_abs_, eps_rel_, a_x_, a_dxdt_;
};

}  // namespace boost::numeric::odeint
