#pragma once
// Reading scene files (the format and its bad-input rules are
// specified in experiments/scenes/README.md).
//
// Every problem with the input throws InputError with one line
//   <file>:<line>: [table] key: what is wrong
// e.g. "scenes/x.toml:12: [body] inertia: expected 3 numbers, got 2".
// Top-level keys have no "[table] " prefix ("x.toml:1: name: ..."); the
// ":<line>" part is left out where no line applies (a key missing from the
// top level or from a table the file does not have, an unreadable file).
// TOML syntax errors read "<file>:<line>: TOML syntax error: <parser message>".
#include <string>
#include <string_view>

#include "experiments/errors/input_error.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// Reads and validates the scene file at `path`. An unreadable or missing
/// file throws InputError naming the file.
lgi::system::Scene read_scene(const std::string& path);

/// Throws InputError naming the file and [suspension] if `scene` is a Cardan
/// top: `command` integrates SO(3) states only (docs/cardan.md §7).
void refuse_cardan_scene(const lgi::system::Scene& scene, const std::string& command);

/// Parses and validates a scene from its TOML text; `path_for_messages` is
/// the file name used in error messages and stored in Scene::file.
lgi::system::Scene parse_scene(std::string_view toml_text, const std::string& path_for_messages);

}  // namespace lgi::experiments
