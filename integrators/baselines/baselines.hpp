#pragma once
// The baselines by name: COORDINATES/STEPPER (`lgi schemes`), what a researcher
// would write instead of using lgi, on the same rigid-body model as the
// Lie-group schemes.
//   COORDINATES  euler-zxz        euler_zxz.hpp        (Trindade & Sampaio 2001, eq. 26–27)
//                rotvec           rotation_vector.hpp  (eq. 25)
//                quat             quaternion.hpp       (q̇ = ½ q ⊗ (0, Ω))
//                quat-normalized  quaternion.hpp       (the same, projected to |q| = 1 after every step)
//                matrix           matrix.hpp           (Ṙ = R Ω̂ in ℝ⁹; R' = W R of seed 002, docs/sources.md)
//   STEPPER      rk4 (fixed step, --dt), dopri5, rkf78, bs, rosenbrock4 (controlled, --tol)
//                odeint_steppers.hpp; the error measure in error_control.hpp;
//                the scheme the time loop drives and the Euler-angle singularity
//                guard in chart_scheme.hpp.
// This header is the non-template entry point; the instantiations live in
// baselines_<coordinates>.cpp (one file per chart, to keep compile units small).
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "integrators/baselines/chart_scheme.hpp"
#include "integrators/system/model.hpp"

namespace lgi::integrators::baselines {

enum class Coordinates { euler_zxz, rotvec, quat, quat_normalized, matrix };
enum class Stepper { rk4, dopri5, rkf78, bs, rosenbrock4 };

inline constexpr std::array<Coordinates, 5> all_coordinates{Coordinates::euler_zxz, Coordinates::rotvec,
                                                            Coordinates::quat, Coordinates::quat_normalized,
                                                            Coordinates::matrix};
inline constexpr std::array<Stepper, 5> all_steppers{Stepper::rk4, Stepper::dopri5, Stepper::rkf78, Stepper::bs,
                                                     Stepper::rosenbrock4};

const char* coordinates_name(Coordinates c);
const char* stepper_name(Stepper s);
/// "euler-zxz/dopri5".
std::string baseline_name(Coordinates c, Stepper s);
struct BaselineId {
  Coordinates coordinates;
  Stepper stepper;
};
/// The baseline a name denotes, if it is one.
std::optional<BaselineId> parse_baseline_name(std::string_view name);
/// Nominal order of the stepper (0 for bs: variable order).
int stepper_order(Stepper s);
bool stepper_is_adaptive(Stepper s);
/// Whether the stepper interpolates output times (its type's dense_output: dopri5).
bool stepper_has_dense_output(Stepper s);

/// Runs one baseline on any scene's model (dispatched once per run).
RunStats run_baseline(Coordinates c, Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg,
                      Observer& observer);

// One function per chart (baselines_<chart>.cpp).
RunStats run_euler_zxz(Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg,
                       Observer& observer);
RunStats run_rotvec(Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer);
RunStats run_quat(bool normalized, Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg,
                  Observer& observer);
RunStats run_matrix(Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer);

/// The stepper switch for one chart, compiled in each baselines_<chart>.cpp.
template <class Coords>
RunStats run_with_stepper(Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg,
                          Observer& observer) {
  return std::visit(
      [&](const auto& m) -> RunStats {
        switch (s) {
          case Stepper::rk4: return run_baseline<Coords, Rk4Stepper>(m, state, cfg, observer);
          case Stepper::dopri5: return run_baseline<Coords, Dopri5Stepper>(m, state, cfg, observer);
          case Stepper::rkf78: return run_baseline<Coords, Rkf78Stepper>(m, state, cfg, observer);
          case Stepper::bs: return run_baseline<Coords, BsStepper>(m, state, cfg, observer);
          case Stepper::rosenbrock4: return run_baseline<Coords, Rosenbrock4Stepper>(m, state, cfg, observer);
        }
        return {};
      },
      model);
}

}  // namespace lgi::integrators::baselines
