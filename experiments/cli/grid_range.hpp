#pragma once
// --l-range / --h-range a:b:n of the atlas commands (lgi region --cells,
// lgi chaos-map; experiments/REGION.md, experiments/CHAOS_MAP.md): n equally
// spaced values from a to b inclusive (n = 1: a alone).
#include <string>
#include <vector>

namespace lgi::experiments {

/// UsageError naming `flag` unless `text` is a:b:n with finite a, b, a <= b
/// (a < b for n > 1) and 1 <= n <= 100000.
std::vector<double> parse_grid_range(const std::string& text, const std::string& flag);

}  // namespace lgi::experiments
