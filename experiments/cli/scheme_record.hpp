#pragma once
// A scheme's registry entry as a record of named fields: `lgi schemes --json`
// prints it (commands/schemes_command.cpp) and lgi.schemes() returns it as a
// dict (python/). One list, so the two never disagree.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "integrators/registry/registry.hpp"

namespace lgi::experiments {

/// One field: null, a flag, an integer or text. `property`: one of the
/// properties the scheme claims (SchemeProperties; lgi.schemes() groups them).
struct SchemeField {
  std::string key;
  std::variant<std::monostate, bool, int, std::string> value;
  bool property = false;
};

/// What a scheme is, from the registry's fields (never from its name):
/// "baseline", "composition", "exact" or "lie-group".
const char* scheme_kind(const integrators::SchemeInfo& s);
/// "free bodies", "conservative" or "all scenes".
const char* scheme_support_text(integrators::SceneSupport s);
/// The scheme's order on a scene with or without torques.
int scheme_order_on(const integrators::SchemeInfo& s, bool has_torque);

/// The fields in the order of `lgi schemes --json`: name, order, family,
/// kind, base, the properties, order_with_torque, order_on_scene (only when
/// `scene_has_torque` is given), implicit, adaptive, dense_output, scenes,
/// lane_kernel (the ensemble kernel its facts declare, or null), reference, notes.
std::vector<SchemeField> scheme_record(const integrators::SchemeInfo& s, std::optional<bool> scene_has_torque);

}  // namespace lgi::experiments
