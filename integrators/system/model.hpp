#pragma once
// The models a scene file can describe, generated from the one list of scene
// terms (terms/scene_terms.hpp), and make_model(), which assembles the one a
// scene declares. Two types: the free body (no torque at all, so schemes
// that need or exploit a torque-free field see it at compile time) and the
// scene model, one Declared<T> slot per scene term. Dispatch on this variant
// happens once per run (std::visit in the registry), never per step.
#include <variant>

#include "integrators/system/rigid_body.hpp"
#include "integrators/system/scene.hpp"
#include "integrators/system/terms/declared_term.hpp"

namespace lgi::system {

using SceneModel = SceneTerms::apply<RigidBody, Declared>;
using HeavyTop = RigidBody<GravityTerm>;  // for code that builds a top directly

using AnyModel = std::variant<FreeBody, SceneModel>;

AnyModel make_model(const Scene& scene);

}  // namespace lgi::system
