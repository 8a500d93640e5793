#include "integrators/system/model.hpp"

namespace lgi::system {

AnyModel make_model(const Scene& scene) {
  const Inertia inertia = make_inertia(scene.inertia);
  GravityTerm gravity;
  if (scene.gravity) gravity = GravityTerm(*scene.mass, scene.gravity->g, *scene.center_of_mass);
  SpringTerm spring;
  if (scene.spring) spring = SpringTerm(scene.spring->stiffness, scene.spring->damping, scene.spring->rest);
  HarmonicDriveTerm drive;
  if (scene.drive) drive = {scene.drive->torque_amplitude, scene.drive->angular_frequency, scene.drive->phase};

  const int key = (scene.gravity ? 1 : 0) | (scene.spring ? 2 : 0) | (scene.drive ? 4 : 0);
  switch (key) {
    case 0: return FreeBody{inertia, {}};
    case 1: return HeavyTop{inertia, {gravity}};
    case 2: return SpringBody{inertia, {spring}};
    case 3: return HeavyTopSpring{inertia, {gravity, spring}};
    case 4: return DrivenBody{inertia, {drive}};
    case 5: return DrivenHeavyTop{inertia, {gravity, drive}};
    case 6: return DrivenSpringBody{inertia, {spring, drive}};
    default: return DrivenHeavyTopSpring{inertia, {gravity, spring, drive}};
  }
}

}  // namespace lgi::system
