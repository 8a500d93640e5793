#pragma once
// `lgi simulate` on a scene with a [suspension] table (the Cardan top,
// docs/cardan.md): the T³ scheme runs on the one time loop
// (integrators/core/stepper_loop.hpp, on system::TorusState) and the trajectory is written in the
// same H5MD layout as every other run (experiments/OUTPUT.md): the body's
// attitude R(q) as a quaternion, its Π = J E(q) q̇ and Ω = E(q) q̇, the
// energy (the whole mechanism's H, rings included), and six scalar
// observables cardan_angle_1..3 (the unwrapped angles, rad) and
// cardan_momentum_1..3 (their conjugate momenta).
#include <atomic>

#include "experiments/cli/simulation.hpp"
#include "integrators/registry/torus_registry.hpp"

namespace lgi::experiments {

/// Whether `lgi simulate` takes the Cardan path: the scene has [suspension].
/// A T³ scheme on a scene without one, or an SO(3) scheme on a scene with
/// one, is a RunError (exit 1) naming both.
bool is_cardan_scene(const system::Scene& scene);
/// Whether `name` is a registered T³ scheme.
bool is_cardan_scheme(const std::string& name);
/// The scheme named `name` for this scene: a T³ scheme on a Cardan scene,
/// an SO(3) scheme on any other. A scheme of the other state space is a
/// UsageError (exit 2) naming both state spaces; an unknown name is
/// scheme_by_name's error. `flag` names the option in the message.
const integrators::SchemeInfo& scheme_for_scene(const system::Scene& scene, const std::string& name,
                                                const std::string& flag);

/// `lgi simulate` for a Cardan scene or a T³ scheme: runs, prints the
/// summary line (unless quiet) and returns the exit status.
int simulate_cardan(const system::Scene& scene, const std::string& scheme_name, const SimulationRequest& request);

/// The run of a Cardan scene with the T³ scheme named `scheme_name`
/// (torus_registry.hpp); settings resolved as for every scheme
/// (step_settings.hpp). Throws UsageError / RunError as run_simulation.
SimulationOutcome run_cardan_simulation(const system::Scene& scene, const std::string& scheme_name,
                                        const SimulationRequest& request, const std::atomic<bool>* stop);

}  // namespace lgi::experiments
