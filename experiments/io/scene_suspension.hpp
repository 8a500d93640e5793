#pragma once
// The [suspension] table of a scene (a Cardan-suspended top, docs/cardan.md
// §6) and the [initial] keys cardan_angles and cardan_rates it needs. Called
// by the scene reader (scene_reader.cpp); every error is one line naming the
// file, the table and the key (scene_toml.hpp), and ends in exit status 2.
#include <array>
#include <string_view>

#include "experiments/io/scene_toml.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// [initial] keys for the Cardan state (only with [suspension]).
inline constexpr std::array<std::string_view, 2> cardan_initial_keys = {"cardan_angles", "cardan_rates"};

/// Reads [suspension] into s.suspension (after [body] and the torque terms).
/// Rejects a tilt outside [0, π], negative ring inertias or masses, a body
/// without a fixed point (no center_of_mass: a free body), and torque terms
/// other than [gravity].
void read_suspension(const scene_toml::Table& suspension, system::Scene& s);

/// With [suspension]: reads cardan_angles and cardan_rates (both required,
/// no other attitude or motion key), sets s.cardan_initial and s.initial
/// (the body's R and Π there). Without: rejects the two keys.
void read_cardan_initial(const scene_toml::Table& initial, system::Scene& s);

/// The Cardan model of a scene with [suspension].
system::CardanTop cardan_top(const system::Scene& s);

}  // namespace lgi::experiments
