#pragma once
// Looking a scheme up by the name a user typed: the registry's entry, or a
// usage error (exit 2) that names the flag and suggests the nearest names.
#include <string>
#include <string_view>
#include <vector>

#include "integrators/registry/registry.hpp"

namespace lgi::experiments {

/// The nearest registered names to `typed` (edit distance to the whole name
/// or to one of its parts between '/', '@'), best first: at most two
/// Lie-group schemes and two baselines; empty if nothing is close.
std::vector<std::string> nearest_scheme_names(std::string_view typed);

/// Every scheme `lgi schemes` and lgi.schemes() list: the SO(3) registry,
/// then the T³ schemes.
std::vector<const integrators::SchemeInfo*> listed_schemes();

/// The registry's entry for `typed`; throws UsageError("<flag>: unknown
/// scheme 'X'; did you mean A, B or C? (lgi schemes lists them)") otherwise.
const integrators::SchemeInfo& scheme_by_name(std::string_view typed, std::string_view flag);

}  // namespace lgi::experiments
