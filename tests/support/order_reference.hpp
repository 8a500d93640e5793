#pragma once
// The references of the order tests at time T from a scene's initial state:
// the exact flow of a free body (integrators/system/free_body_exact.hpp), and
// the independent odeint reference of a scene with torques (reference_solution.hpp).
#include <catch2/catch.hpp>

#include <variant>

#include "integrators/system/free_body_exact.hpp"
#include "integrators/system/model.hpp"
#include "reference_solution.hpp"

namespace lgi::testing {

inline system::State exact_free_body_at(const system::AnyModel& model, const system::Scene& scene, double T) {
  return system::FreeBodyExactFlow(std::get<system::FreeBody>(model).inertia, scene.initial).at(T);
}

/// The test fails unless the scene's model is a SceneModel (a scene with torque terms).
inline system::State scene_reference_at(const system::AnyModel& model, const system::Scene& scene, double T) {
  REQUIRE(std::holds_alternative<system::SceneModel>(model));
  return reference_solution(std::get<system::SceneModel>(model), scene.initial, 0.0, T);
}

}  // namespace lgi::testing
