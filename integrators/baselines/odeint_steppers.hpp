#pragma once
// The Boost.Odeint steppers behind the baselines, behind one small interface
// ChartScheme (chart_scheme.hpp) drives, and the counting system functor.
//
//   rk4          odeint::runge_kutta4 (classical RK4, Kutta 1901), fixed step.
//   dopri5       odeint::controlled_runge_kutta<runge_kutta_dopri5> (Dormand &
//                Prince, J. Comput. Appl. Math. 6 (1980)): FSAL, 6 evaluations
//                per attempt, dense output of order 4 (Shampine 1986, odeint's
//                calc_state) for output at given times.
//   rkf78        odeint::controlled_runge_kutta<runge_kutta_fehlberg78>
//                (Fehlberg, NASA TR R-287 (1968)): 13 evaluations per attempt,
//                the derivative at the step's start reused across rejections.
//   bs           odeint::bulirsch_stoer (Deuflhard's order and step control,
//                HNW I §II.9): variable order, modified midpoint + extrapolation.
//   rosenbrock4  odeint's rosenbrock4 method (RODAS 4(3), Hairer & Wanner II
//                §VI.4; odeint's default_rosenbrock_coefficients): 6 evaluations,
//                one analytic Jacobian (the chart's jacobian()) and one LU per
//                attempt. Its stage loop and controller are transcribed below
//                to Eigen fixed-size types (see Rosenbrock4Stepper for why).
// Every controlled stepper measures the error as error_control.hpp says.
//
// States are std::array<double, N> with odeint's array algebra: no stepper
// allocates per step, with one exception inside odeint that we document
// rather than patch: bulirsch_stoer::try_step builds two std::vector(9) of
// step-size and work estimates per call (and its extrapolation table once).
//
// Counting: the system functor handed to odeint increments
// WorkCounters::rhs_evaluations on every call (Jacobian evaluations of
// rosenbrock4 are not right-hand-side evaluations and are not counted there).
#include <Eigen/Core>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <Eigen/LU>
#include <boost/numeric/odeint/stepper/rosenbrock4.hpp>  // default_rosenbrock_coefficients only
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "integrators/baselines/error_control.hpp"

namespace lgi::integrators::baselines {

namespace odeint = boost::numeric::odeint;

/// What the right-hand side saw during one attempted step: the smallest
/// |sinθ| and the largest |ψ̇| of the Euler-angle chart. Only used by
/// euler-zxz; reset by ChartScheme before every attempt.
struct ChartWatch {
  double min_margin = std::numeric_limits<double>::infinity();
  double theta_at_min = 0.0;
  double t_at_min = 0.0;
  double max_precession_rate = 0.0;
  void reset() {
    min_margin = std::numeric_limits<double>::infinity();
    max_precession_rate = 0.0;
  }
};

/// The system functor given to odeint: counts calls, evaluates the chart's
/// right-hand side, and for Euler angles records what ChartWatch needs.
template <class Coords, class Model>
struct CountingSystem {
  using Vector = typename Coords::Vector;
  const Model* model = nullptr;
  std::int64_t* evaluations = nullptr;
  ChartWatch* watch = nullptr;

  void operator()(const Vector& x, Vector& dxdt, double t) const {
    ++*evaluations;
    Coords::rhs(*model, x, dxdt, t);
    if constexpr (Coords::euler_angle_chart) {
      const double margin = std::abs(std::sin(x[1]));
      if (margin < watch->min_margin) {
        watch->min_margin = margin;
        watch->theta_at_min = x[1];
        watch->t_at_min = t;
      }
      const double rate = std::abs(dxdt[0]);
      if (!(rate <= watch->max_precession_rate)) watch->max_precession_rate = rate;  // NaN sticks
    }
  }
};

template <class Coords>
using BaselineRk4 = odeint::runge_kutta4<typename Coords::Vector, double, typename Coords::Vector, double,
                                         BaselineAlgebra<Coords>, odeint::default_operations>;
template <class Coords>
using BaselineDopri5 =
    odeint::controlled_runge_kutta<odeint::runge_kutta_dopri5<typename Coords::Vector, double, typename Coords::Vector,
                                                              double, BaselineAlgebra<Coords>,
                                                              odeint::default_operations>>;
template <class Coords>
using BaselineRkf78 = odeint::controlled_runge_kutta<
    odeint::runge_kutta_fehlberg78<typename Coords::Vector, double, typename Coords::Vector, double,
                                   BaselineAlgebra<Coords>, odeint::default_operations>>;
template <class Coords>
using BaselineBs = odeint::bulirsch_stoer<typename Coords::Vector, double, typename Coords::Vector, double,
                                          BaselineAlgebra<Coords>, odeint::default_operations>;

// odeint's controlled_runge_kutta and bulirsch_stoer constructors copy a
// default-constructed stepper whose std::array work space is uninitialised
// (harmless: it is written before it is read); GCC reports that copy at our
// constructors. Silenced for the stepper classes only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

// ---- the interface ChartScheme drives ----------------------------------------
// Fixed step:  step(sys, x, t, h).
// Controlled:  attempt(sys, x, t, h) → accepted? (x advanced; h the proposal
//              for the next attempt either way); derivative(): the cached
//              ẋ at x or nullptr; state_changed(derivative_updated) after the
//              chart projected x between steps; interpolate(t, out) where
//              dense_output.

template <class Coords>
class Rk4Stepper {
 public:
  using Vector = typename Coords::Vector;
  static constexpr bool adaptive = false;
  static constexpr bool dense_output = false;  // every stepper states it (chart_scheme.hpp's constraints read it)
  static constexpr const char* name = "rk4";
  explicit Rk4Stepper(double /*tol*/ = 0.0) {}
  template <class Sys>
  void step(const Sys& sys, Vector& x, double t, double h) {
    stepper_.do_step(sys, x, t, h);
  }

 private:
  BaselineRk4<Coords> stepper_;
};

/// Shared by the steppers that keep ẋ at the current state across attempts.
template <class Coords>
class CachedDerivative {
 public:
  using Vector = typename Coords::Vector;
  Vector* derivative() { return fresh_ ? &dxdt_ : nullptr; }
  void state_changed(bool derivative_updated) {
    if (!derivative_updated) fresh_ = false;
  }

 protected:
  template <class Sys>
  const Vector& ensure(const Sys& sys, const Vector& x, double t) {
    if (!fresh_) {
      sys(x, dxdt_, t);
      fresh_ = true;
    }
    return dxdt_;
  }
  Vector dxdt_{};
  bool fresh_ = false;
};

template <class Coords>
class Dopri5Stepper : public CachedDerivative<Coords> {
 public:
  using Vector = typename Coords::Vector;
  static constexpr bool adaptive = true;
  static constexpr bool dense_output = true;
  static constexpr int error_order = 4;
  static constexpr const char* name = "dopri5";
  explicit Dopri5Stepper(double tol) : controller_(typename BaselineDopri5<Coords>::error_checker_type(tol, tol, 1.0, 1.0)) {}

  template <class Sys>
  bool attempt(const Sys& sys, Vector& x, double t, double& h) {
    this->ensure(sys, x, t);
    double tt = t;
    if (controller_.try_step(sys, x, this->dxdt_, tt, x_new_, dxdt_new_, h) != odeint::success) return false;
    x_old_ = x;
    dxdt_old_ = this->dxdt_;
    t_old_ = t;
    t_new_ = tt;
    x = x_new_;
    this->dxdt_ = dxdt_new_;
    return true;
  }
  /// The state at t in [t_old, t_new] of the last accepted step (before any
  /// projection the chart applied afterwards).
  void interpolate(double t, Vector& out) const {
    controller_.stepper().calc_state(t, out, x_old_, dxdt_old_, t_old_, x_new_, dxdt_new_, t_new_);
  }

 private:
  BaselineDopri5<Coords> controller_;
  Vector x_new_{}, dxdt_new_{}, x_old_{}, dxdt_old_{};
  double t_old_ = 0.0, t_new_ = 0.0;
};

template <class Coords, class Controller, int ErrorOrder, const char* Name>
class CachedControlledStepper : public CachedDerivative<Coords> {
 public:
  using Vector = typename Coords::Vector;
  static constexpr bool adaptive = true;
  static constexpr bool dense_output = false;
  static constexpr int error_order = ErrorOrder;
  static constexpr const char* name = Name;

  template <class Sys>
  bool attempt(const Sys& sys, Vector& x, double t, double& h) {
    this->ensure(sys, x, t);
    double tt = t;
    if (controller_.try_step(sys, x, this->dxdt_, tt, x_new_, h) != odeint::success) return false;
    x = x_new_;
    this->fresh_ = false;  // evaluated lazily at the next attempt (after any projection)
    return true;
  }
  void interpolate(double, Vector&) const {}

 protected:
  // The controller is built in place (copying an odeint stepper copies its
  // uninitialised work arrays).
  template <class... Args>
  explicit CachedControlledStepper(Args&&... args) : controller_(std::forward<Args>(args)...) {}
  Controller controller_;
  Vector x_new_{};
};

inline constexpr char rkf78_name[] = "rkf78";
inline constexpr char bs_name[] = "bs";

template <class Coords>
class Rkf78Stepper : public CachedControlledStepper<Coords, BaselineRkf78<Coords>, 7, rkf78_name> {
  using Base = CachedControlledStepper<Coords, BaselineRkf78<Coords>, 7, rkf78_name>;

 public:
  explicit Rkf78Stepper(double tol)
      : Base(typename BaselineRkf78<Coords>::error_checker_type(tol, tol, 1.0, 1.0)) {}
};

template <class Coords>
class BsStepper : public CachedControlledStepper<Coords, BaselineBs<Coords>, 4, bs_name> {
  using Base = CachedControlledStepper<Coords, BaselineBs<Coords>, 4, bs_name>;

 public:
  explicit BsStepper(double tol) : Base(tol, tol, 1.0, 1.0) {}
};

/// rosenbrock4: odeint's method (its default_rosenbrock_coefficients, the
/// RODAS 4(3) pair of Hairer & Wanner II §VI.4 in the formulation of HW's
/// rodas.f, 6 evaluations and one Jacobian per attempt), with the analytic
/// Jacobian of the chart's right-hand side. The stage loop is odeint's
/// rosenbrock4::do_step, transcribed to Eigen fixed-size types: odeint's class
/// keeps its state in uBLAS containers, and Boost 1.74's uBLAS storage calls
/// std::allocator::construct, which C++20 removed, so it does not compile in
/// this project (fixed upstream in later Boost releases). The LU is Eigen's
/// PartialPivLU on the fixed-size matrix I/(γh) − J: nothing allocates.
/// Step-size control: that of odeint's rosenbrock4_controller (HW II §IV.8,
/// with the predictive (Gustafsson) variant), on error_control.hpp's measure
/// with |Ω| taken as max(|Ω_n|, |Ω_n+1|).
/// One coefficient differs from Boost 1.74: the time-derivative weight d4 is
/// −0.03620000000000023, as in Hairer & Wanner's rodas.f (RODCOE, METH = 1);
/// odeint's default_rosenbrock_coefficients has +0.0362, which makes the method
/// first order on a time-dependent field (d4 multiplies ∂f/∂t). Measured on
/// the driven general top (tests/test_stated_orders.cpp, adaptive order):
/// slope 1.00 against the mean step with odeint's sign, 4 with rodas.f's.
/// Autonomous scenes (∂f/∂t = 0) are not affected.
template <class Coords>
class Rosenbrock4Stepper {
 public:
  using Vector = typename Coords::Vector;
  using Vec = Eigen::Matrix<double, static_cast<int>(Coords::size), 1>;
  static constexpr bool adaptive = true;
  static constexpr bool dense_output = false;
  static constexpr int error_order = 3;
  static constexpr const char* name = "rosenbrock4";

  explicit Rosenbrock4Stepper(double tol) : tol_(tol) {}
  /// rodas.f's D4 (the header above); the other coefficients are odeint's.
  static constexpr double rodas_d4 = -0.3620000000000023e-01;

  Vector* derivative() { return nullptr; }  // each attempt evaluates ẋ at x itself
  void state_changed(bool) {}
  void interpolate(double, Vector&) const {}

  template <class Sys>
  bool attempt(const Sys& sys, Vector& x, double t, double& h) {
    const auto& c = coef_;
    Vector xt{}, f{}, dfdt{};
    auto vec = [](const Vector& a) { return Eigen::Map<const Vec>(a.data()); };
    sys(x, f, t);
    typename Coords::Jacobian J;
    Coords::jacobian(*sys.model, x, J, dfdt, t);
    ++jacobian_evaluations_;
    lu_.compute(Coords::Jacobian::Identity() / (c.gamma * h) - J);
    const Vec x0 = vec(x), dft = vec(dfdt);
    auto stage = [&](const Vec& arg, double tc, Vec& g, const Vec& rhs_extra) {
      Eigen::Map<Vec>(xt.data()) = arg;
      sys(xt, f, tc);
      g = lu_.solve(vec(f) + rhs_extra);
    };
    const Vec g1 = lu_.solve(vec(f) + h * c.d1 * dft);
    Vec g2, g3, g4, g5, err;
    stage(x0 + c.a21 * g1, t + c.c2 * h, g2, h * c.d2 * dft + c.c21 * g1 / h);
    stage(x0 + c.a31 * g1 + c.a32 * g2, t + c.c3 * h, g3, h * c.d3 * dft + (c.c31 * g1 + c.c32 * g2) / h);
    stage(x0 + c.a41 * g1 + c.a42 * g2 + c.a43 * g3, t + c.c4 * h, g4,
          h * rodas_d4 * dft + (c.c41 * g1 + c.c42 * g2 + c.c43 * g3) / h);
    const Vec x5 = x0 + c.a51 * g1 + c.a52 * g2 + c.a53 * g3 + c.a54 * g4;
    stage(x5, t + h, g5, (c.c51 * g1 + c.c52 * g2 + c.c53 * g3 + c.c54 * g4) / h);
    const Vec x6 = x5 + g5;
    stage(x6, t + h, err, (c.c61 * g1 + c.c62 * g2 + c.c63 * g3 + c.c64 * g4 + c.c65 * g5) / h);
    const Vec x_out = x6 + err;

    const std::size_t o = Coords::omega_offset;
    const double w = std::sqrt(std::max(x0.segment(static_cast<Eigen::Index>(o), 3).squaredNorm(),
                                        x_out.segment(static_cast<Eigen::Index>(o), 3).squaredNorm()));
    Vector err_a{};
    Eigen::Map<Vec>(err_a.data()) = err;
    const double e = weighted_error<Coords>(err_a, w, tol_, tol_);
    // h_new = h / clamp(err^(1/4)/0.9, 1/6, 5), as odeint's rosenbrock4_controller.
    constexpr double safe = 0.9, fac_max = 5.0, fac_min = 1.0 / 6.0;
    double fac = std::max(fac_min, std::min(fac_max, std::pow(e, 0.25) / safe));
    if (!(e <= 1.0)) {
      h = h / (std::isfinite(fac) ? fac : fac_max);
      last_rejected_ = true;
      return false;
    }
    if (!first_) {
      double fac_pred = (h_old_ / h) * std::pow(e * e / err_old_, 0.25) / safe;
      fac_pred = std::max(fac_min, std::min(fac_max, fac_pred));
      fac = std::max(fac, fac_pred);
    }
    first_ = false;
    double h_new = h / fac;
    h_old_ = h;
    err_old_ = std::max(0.01, e);
    if (last_rejected_) h_new = std::min(h_new, h);
    last_rejected_ = false;
    Eigen::Map<Vec>(x.data()) = x_out;
    h = h_new;
    return true;
  }
  std::int64_t jacobian_evaluations() const { return jacobian_evaluations_; }

 private:
  odeint::default_rosenbrock_coefficients<double> coef_;
  Eigen::PartialPivLU<typename Coords::Jacobian> lu_{static_cast<Eigen::Index>(Coords::size)};
  double tol_;
  bool first_ = true, last_rejected_ = false;
  double h_old_ = 0.0, err_old_ = 0.0;
  std::int64_t jacobian_evaluations_ = 0;
};

#pragma GCC diagnostic pop

}  // namespace lgi::integrators::baselines
