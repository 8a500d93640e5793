#pragma once
// J and m g χ of a shipped heavy top or free body (the atlas analyses' HeavyTopBody),
// for the tests that call the analysis layer directly.
#include "experiments/analysis/relative_equilibria.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::testing {

inline experiments::HeavyTopBody body_of(const system::Scene& s) {
  experiments::HeavyTopBody b;
  b.J = s.inertia;
  if (s.declared<system::GravityTerm>())
    b.weight = *s.mass * s.declared<system::GravityTerm>()->g * s.center_of_mass.value_or(lie::Vec3::Zero());
  return b;
}

}  // namespace lgi::testing
