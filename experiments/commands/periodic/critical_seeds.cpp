#include "experiments/commands/periodic/critical_seeds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "experiments/analysis/kovalevskaya_diagram.hpp"
#include "experiments/analysis/periodic/kovalevskaya_orbits.hpp"
#include "experiments/errors/exit_status.hpp"

namespace lgi::experiments {

std::vector<SectionSeed> critical_seeds(const HeavyTopBody& body, const std::string& scene, double l,
                                        const std::string& energies, double dt) {
  if (!kovalevskaya_scale(body))
    throw UsageError("--from-critical: " + scene + " is not a Kovalevskaya top (J = J3 diag(2, 2, 1), m g chi along e1)");
  std::vector<double> hs;
  std::stringstream in(energies);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double h = NAN;
    try {
      h = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || item.find_first_not_of(" \t", used) != std::string::npos || !std::isfinite(h))
      throw UsageError("--from-critical: '" + energies + "' is not a list of energies");
    hs.push_back(h);
  }
  if (hs.empty()) throw UsageError("--from-critical: give one or more energies H1,H2,...");
  std::vector<SectionSeed> seeds;
  for (const double h : hs) {
    const std::vector<CriticalSeed> found = kovalevskaya_critical_seeds(body, l, h, dt);
    if (found.empty()) {
      SectionSeed none;
      none.failure = "--from-critical h = " + std::to_string(h) + ": no critical circle found";
      seeds.push_back(none);
    }
    for (const CriticalSeed& c : found) {
      char label[96];
      std::snprintf(label, sizeof label, "critical value (h, k) = (%.9g, %.9g)", c.h, c.k);
      seeds.push_back({c.x, c.period, label, c.failure, c.h});
    }
  }
  return seeds;
}

void append_appelrot_columns(const HeavyTopBody& body, const std::vector<FamilyOrbit>& rows,
                             std::vector<TableColumn>& columns) {
  TableColumn k{"k"}, family{"appelrot_family", 1, true}, distance{"appelrot_distance"}, gap{"critical_rank_gap"};
  for (const FamilyOrbit& r : rows) {
    const AppelrotCheck a = appelrot_check(body, r.orbit.x0, r.orbit.l, r.orbit.h);
    k.real.push_back(a.k), family.whole.push_back(a.family), distance.real.push_back(a.distance);
    gap.real.push_back(a.rank_gap);
  }
  for (TableColumn* c : {&k, &family, &distance, &gap}) columns.push_back(std::move(*c));
}

std::string appelrot_summary(const HeavyTopBody& body, const std::vector<FamilyOrbit>& rows) {
  if (!kovalevskaya_scale(body)) return "";
  double worst = 0.0;
  int isolated = 0, on_family = 0;
  for (const FamilyOrbit& r : rows) {
    if (r.orbit.degenerate) continue;
    const AppelrotCheck a = appelrot_check(body, r.orbit.x0, r.orbit.l, r.orbit.h);
    ++isolated, on_family += a.family >= 0 ? 1 : 0;
    worst = std::max(worst, a.distance);
  }
  char line[200];
  std::snprintf(line, sizeof line,
                "Kovalevskaya top: %d of %d isolated orbit(s) on an Appelrot family (within 1e-6); largest "
                "appelrot_distance %.2e",
                on_family, isolated, worst);
  return line;
}

}  // namespace lgi::experiments
