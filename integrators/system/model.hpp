#pragma once
// The closed set of models a scene file can describe, and make_model(),
// which assembles the one a scene declares. Dispatch on this variant happens
// once per run (std::visit in the registry), never per step.
#include <variant>

#include "integrators/system/rigid_body.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::system {

using HeavyTop = RigidBody<GravityTerm>;
using SpringBody = RigidBody<SpringTerm>;
using HeavyTopSpring = RigidBody<GravityTerm, SpringTerm>;
using DrivenBody = RigidBody<HarmonicDriveTerm>;
using DrivenHeavyTop = RigidBody<GravityTerm, HarmonicDriveTerm>;
using DrivenSpringBody = RigidBody<SpringTerm, HarmonicDriveTerm>;
using DrivenHeavyTopSpring = RigidBody<GravityTerm, SpringTerm, HarmonicDriveTerm>;

using AnyModel = std::variant<FreeBody, HeavyTop, SpringBody, HeavyTopSpring, DrivenBody, DrivenHeavyTop,
                              DrivenSpringBody, DrivenHeavyTopSpring>;

AnyModel make_model(const Scene& scene);

}  // namespace lgi::system
