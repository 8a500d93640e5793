// Names and dispatch of the Boost.Odeint baselines (baselines.hpp).
#include "integrators/baselines/baselines.hpp"

namespace lgi::integrators::baselines {

const char* coordinates_name(Coordinates c) {
  switch (c) {
    case Coordinates::euler_zxz: return "euler-zxz";
    case Coordinates::rotvec: return "rotvec";
    case Coordinates::quat: return "quat";
    case Coordinates::quat_normalized: return "quat-normalized";
    case Coordinates::matrix: return "matrix";
  }
  return "";
}

const char* stepper_name(Stepper s) {
  switch (s) {
    case Stepper::rk4: return "rk4";
    case Stepper::dopri5: return "dopri5";
    case Stepper::rkf78: return "rkf78";
    case Stepper::bs: return "bs";
    case Stepper::rosenbrock4: return "rosenbrock4";
  }
  return "";
}

std::string baseline_name(Coordinates c, Stepper s) {
  return std::string(coordinates_name(c)) + "/" + stepper_name(s);
}

std::optional<BaselineId> parse_baseline_name(std::string_view name) {
  for (Coordinates c : all_coordinates)
    for (Stepper s : all_steppers)
      if (name == baseline_name(c, s)) return BaselineId{c, s};
  return std::nullopt;
}

int stepper_order(Stepper s) {
  switch (s) {
    case Stepper::rk4: return 4;
    case Stepper::dopri5: return 5;
    case Stepper::rkf78: return 8;
    case Stepper::bs: return 0;
    case Stepper::rosenbrock4: return 4;
  }
  return 0;
}

bool stepper_is_adaptive(Stepper s) { return s != Stepper::rk4; }

bool stepper_has_dense_output(Stepper s) { return s == Stepper::dopri5; }

RunStats run_baseline(Coordinates c, Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg,
                      Observer& observer) {
  switch (c) {
    case Coordinates::euler_zxz: return run_euler_zxz(s, model, state, cfg, observer);
    case Coordinates::rotvec: return run_rotvec(s, model, state, cfg, observer);
    case Coordinates::quat: return run_quat(false, s, model, state, cfg, observer);
    case Coordinates::quat_normalized: return run_quat(true, s, model, state, cfg, observer);
    case Coordinates::matrix: return run_matrix(s, model, state, cfg, observer);
  }
  return {};
}

}  // namespace lgi::integrators::baselines
