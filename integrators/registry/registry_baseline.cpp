// Registry lines for: COORDS/STEPPER baselines through Boost.Odeint
// (integrators/baselines/baselines.hpp): every chart × every stepper.
#include "integrators/baselines/baselines.hpp"
#include "integrators/registry/registry_support.hpp"

namespace lgi::integrators {
namespace {

using baselines::Coordinates;
using baselines::Stepper;

template <Coordinates C, Stepper S>
RunStats run_registered_baseline(const system::AnyModel& model, State& state, const RunConfig& cfg,
                                 Observer& observer) {
  return baselines::run_baseline(C, S, model, state, cfg, observer);
}

template <Coordinates C>
RunFunction run_function(Stepper s) {
  switch (s) {
    case Stepper::rk4: return &run_registered_baseline<C, Stepper::rk4>;
    case Stepper::dopri5: return &run_registered_baseline<C, Stepper::dopri5>;
    case Stepper::rkf78: return &run_registered_baseline<C, Stepper::rkf78>;
    case Stepper::bs: return &run_registered_baseline<C, Stepper::bs>;
    case Stepper::rosenbrock4: return &run_registered_baseline<C, Stepper::rosenbrock4>;
  }
  return nullptr;
}

RunFunction run_function(Coordinates c, Stepper s) {
  switch (c) {
    case Coordinates::euler_zxz: return run_function<Coordinates::euler_zxz>(s);
    case Coordinates::rotvec: return run_function<Coordinates::rotvec>(s);
    case Coordinates::quat: return run_function<Coordinates::quat>(s);
    case Coordinates::quat_normalized: return run_function<Coordinates::quat_normalized>(s);
    case Coordinates::matrix: return run_function<Coordinates::matrix>(s);
  }
  return nullptr;
}

std::string coordinates_reference(Coordinates c) {
  switch (c) {
    case Coordinates::euler_zxz:
      return "Euler angles ZXZ and body angular velocity: Trindade & Sampaio, J. Braz. Soc. Mech. Sci. 23 (2001), "
             "eq. 26-27";
    case Coordinates::rotvec:
      return "rotation vector and body angular velocity: Trindade & Sampaio (2001), eq. 25";
    case Coordinates::quat:
    case Coordinates::quat_normalized:
      return "unit quaternion and body angular velocity, q' = q (0, Omega)/2";
    case Coordinates::matrix:
      return "attitude matrix in R^9 and body angular velocity, R' = R hat(Omega) (the R' = W R of the EduRev prism notes, seed 002)";
  }
  return {};
}

std::string stepper_reference(Stepper s) {
  switch (s) {
    case Stepper::rk4: return "odeint runge_kutta4 (classical RK4)";
    case Stepper::dopri5:
      return "odeint runge_kutta_dopri5, controlled, dense output (Dormand & Prince, J. Comput. Appl. Math. 6 (1980))";
    case Stepper::rkf78: return "odeint runge_kutta_fehlberg78, controlled (Fehlberg, NASA TR R-287 (1968))";
    case Stepper::bs: return "odeint bulirsch_stoer (Deuflhard, Numer. Math. 41 (1983); HNW I II.9)";
    case Stepper::rosenbrock4:
      return "odeint rosenbrock4 (Kaps & Rentrop, Numer. Math. 33 (1979); HW II IV.7) with the analytic Jacobian";
  }
  return {};
}

std::string notes(Coordinates c, Stepper s) {
  std::string n;
  if (s == Stepper::rk4) n = "fixed step (--dt)";
  else n = "controlled (--tol): abs = rel = tol, attitude coordinates absolute, Omega relative to |Omega|";
  if (s == Stepper::bs) n += "; variable order (odeint resizes its extrapolation tables, so steps may allocate)";
  if (s == Stepper::rosenbrock4) n += "; linearly implicit (one LU per step)";
  switch (c) {
    case Coordinates::euler_zxz:
      n += "; stops at the Euler-angle singularity (|sin theta| < 1e-6, a step across theta = 0 or pi";
      n += s == Stepper::rk4 ? ", or h |psidot| > 0.1)" : ")";
      break;
    case Coordinates::rotvec: n += "; chart switch Psi -> Psi (1 - 2 pi/|Psi|) when |Psi| > pi"; break;
    case Coordinates::quat: n += "; |q| drifts (not normalised, shown by orthogonality_error)"; break;
    case Coordinates::quat_normalized: n += "; projection q <- q/|q| after every step"; break;
    case Coordinates::matrix: n += "; R^T R drifts (shown by orthogonality_error)"; break;
  }
  return n;
}

}  // namespace

void add_baseline_schemes(std::vector<SchemeInfo>& r) {
  for (Coordinates c : baselines::all_coordinates) {
    for (Stepper s : baselines::all_steppers) {
      r.push_back({.name = baselines::baseline_name(c, s),
                   .order = baselines::stepper_order(s),
                   .family = std::string("baseline ") + baselines::coordinates_name(c),  // one family per chart
                   .properties = {.adaptive = baselines::stepper_is_adaptive(s),
                                  .dense_output = baselines::stepper_has_dense_output(s),
                                  .baseline = true,
                                  .euler_angle_chart = c == Coordinates::euler_zxz},
                   .support = SceneSupport::any,
                   .reference = coordinates_reference(c) + "; " + stepper_reference(s),
                   .notes = notes(c, s),
                   .run = run_function(c, s),
                   .locates_events = false});
    }
  }
}

}  // namespace lgi::integrators
