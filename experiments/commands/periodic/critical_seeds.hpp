#pragma once
// `lgi periodic --from-critical H1,H2,...` and the Kovalevskaya columns of
// /periodic (experiments/PERIODIC.md "Kovalevskaya's top: critical orbits"):
// seeds on the critical circles of the Kovalevskaya top at the given
// energies, and per orbit k = K/c², its nearest Appelrot family, the distance
// from it and the rank gap of (dH, dK, dC, d|Γ|²).
#include <string>
#include <vector>

#include "experiments/analysis/periodic/family_continuation.hpp"
#include "experiments/commands/periodic/periodic_seeds.hpp"
#include "experiments/io/table_file.hpp"

namespace lgi::experiments {

/// The seeds of --from-critical: one per critical circle found at each energy of
/// `energies` (comma-separated, unscaled) at ℓ = l. UsageError naming the flag on a
/// malformed list or a body that is not a Kovalevskaya top (`scene` names it);
/// an energy with no critical circle gives a seed with a failure.
std::vector<SectionSeed> critical_seeds(const HeavyTopBody& body, const std::string& scene, double l,
                                        const std::string& energies, double dt);

/// Appends k, appelrot_family, appelrot_distance and critical_rank_gap (NaN, −1 on
/// a top that is not Kovalevskaya's) to the /periodic columns of `rows`.
void append_appelrot_columns(const HeavyTopBody& body, const std::vector<FamilyOrbit>& rows,
                             std::vector<TableColumn>& columns);

/// On a Kovalevskaya top, one line: the largest appelrot_distance over the orbits that
/// are not degenerate, and how many lie on a family; "" otherwise.
std::string appelrot_summary(const HeavyTopBody& body, const std::vector<FamilyOrbit>& rows);

}  // namespace lgi::experiments
