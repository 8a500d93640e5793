#pragma once
// The state of the Cardan top (integrators/system/cardan.hpp): a point of
// T³ × ℝ³, the Cardan angles carried unwrapped on the universal cover ℝ³ of
// T³ and their conjugate momenta (docs/cardan.md §3).
#include "lie/so3.hpp"

namespace lgi::system {

struct TorusState {
  lie::Vec3 q = lie::Vec3::Zero();
  lie::Vec3 p = lie::Vec3::Zero();
};

}  // namespace lgi::system
