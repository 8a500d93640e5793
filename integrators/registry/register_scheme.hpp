#pragma once
// Registering a scheme type from outside lgi's tree (docs/extending.md,
// examples/custom_scheme/): the type carries its facts (scheme_facts.hpp)
// and its step (scheme_interface.hpp); this adds its registry line, read
// from those facts as for every in-tree scheme (registry_support.hpp):
//
//   lgi::integrators::register_scheme<MyScheme>({.name = "my-scheme", .family = "RKMK"});
//
// after which `find_scheme("my-scheme")` runs it through the one time loop.
#include <vector>

#include "integrators/registry/registry.hpp"
#include "integrators/registry/registry_support.hpp"

namespace lgi::integrators {

template <SchemeWithFacts Scheme>
void register_scheme(const SchemeEntry& entry) {
  std::vector<SchemeInfo> line;
  add_scheme<Scheme>(line, entry);
  register_scheme(std::move(line.front()));
}

}  // namespace lgi::integrators
