#pragma once
// Runs for the Boost.Odeint baseline tests (integrators/baselines/): a shipped
// scene by name, a baseline run to its final state (no output), the rkmk4
// state at a small step as the reference, and the attitude error between two
// attitude matrices.
// First: it includes odeint with a GCC false positive silenced (see there).
#include "reference_solution.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

#include "experiments/io/scene_reader.hpp"
#include "integrators/baselines/baselines.hpp"
#include "integrators/registry/registry.hpp"
#include "lie/quaternion.hpp"
#include "lie/so3.hpp"

namespace lgi::testing {

inline const std::string scenes = LGI_SCENES_DIR;

inline system::Scene scene(const std::string& name) {
  return experiments::read_scene(scenes + "/" + name + ".toml");
}

/// Final state of a baseline run (no output), REQUIRE-ing success unless told otherwise.
inline integrators::RunStats run(integrators::baselines::Coordinates c, integrators::baselines::Stepper s,
                                 const system::AnyModel& model, system::State& x, double t_end, double dt_or_tol) {
  integrators::RunConfig cfg;
  cfg.t_end = t_end;
  if (integrators::baselines::stepper_is_adaptive(s)) cfg.tol = dt_or_tol;
  else cfg.dt = dt_or_tol;
  cfg.save_every = std::int64_t{1} << 40;
  integrators::NullObserver none;
  return integrators::baselines::run_baseline(c, s, model, x, cfg, none);
}

inline system::State rkmk4_at(const system::AnyModel& model, const system::State& x0, double t_end, double h) {
  system::State x = x0;
  integrators::RunConfig cfg;
  cfg.t_end = t_end;
  cfg.dt = h;
  cfg.save_every = std::int64_t{1} << 40;
  integrators::NullObserver none;
  REQUIRE(integrators::find_scheme("rkmk4")->run(model, x, cfg, none).ok);
  return x;
}

/// The attitude error of docs/conventions.md §7; a non-orthogonal R (quat, matrix) is
/// compared through its nearest rotation (the quaternion Shepperd extracts).
inline double attitude_error(const lie::Mat3& R, const lie::Mat3& ref) {
  return lie::quat_distance(lie::quat_from_matrix(ref), lie::quat_from_matrix(R).normalized());
}

}  // namespace lgi::testing
