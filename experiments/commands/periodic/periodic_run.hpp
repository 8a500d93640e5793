#pragma once
// The families of `lgi periodic` from its starts (experiments/PERIODIC.md):
// the Lyapunov families of the equilibria, seeds (a point and a period), a
// Kovalevskaya top's critical orbits (--from-critical), or
// the seeds of a poincare file on its section, with the manifolds of their
// hyperbolic first orbits. Shared by the command and the Python module.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "experiments/analysis/periodic/lyapunov_families.hpp"
#include "experiments/commands/periodic/periodic_tables.hpp"

namespace lgi::experiments {

/// Why a Cardan top has no reduced flow for lgi periodic: "" when its outer
/// angle is cyclic (tilt 0, or no gravity), else one line naming the scene file
/// and suspension.tilt (the command prefixes "--scene: ", the Python module its function).
std::string cardan_tilt_refusal(const system::CardanTop& top, const std::string& scene_file);

struct PeriodicRequest {
  /// Called after each start (an equilibrium's mode, a seed) with the starts done and their
  /// number; false stops there (a signal): that start is dropped (the signal may have cut it
  /// short), the families of the starts before it are returned, no manifolds.
  using StartDone = std::function<bool(std::size_t, std::size_t)>;
  FamilySettings settings{};
  std::optional<double> l;         // required unless poincare is given (then it must equal the file's)
  bool from_equilibria = false;
  std::vector<std::pair<Vec6, double>> seeds;  // points and period guesses
  std::string critical, scene_file;             // --from-critical H1,H2,... (a Kovalevskaya top) and its scene
  std::string poincare, poincare_rows;          // a poincare file and its rows (--poincare-rows)
  std::vector<std::string> poincare_points;     // --poincare-point
  int returns = 1;
  double direction = 1.0;          // the sense of the first step (the sign of --l-step)
  ManifoldSettings manifolds{};    // points = 0: none
  StartDone start_done;            // empty: none
};

struct PeriodicResult {
  std::vector<FamilyOrbit> rows;
  std::vector<RowManifolds> manifolds;
  std::vector<std::string> failures;  // starts with no family, manifolds not grown
  double l = 0.0;
  std::optional<PhaseSection> section;
  std::size_t starts = 0, starts_kept = 0;  // the starts, and those whose families are in `rows`
  bool stopped = false;                     // start_done returned false
};

/// The families of exactly one kind of start of `r` (UsageError naming the
/// flag on a poincare file that does not fit). A Cardan top (flow.cardan)
/// takes --from-equilibria, seeds (x = (q, p); q1 is set to 0, p1 must
/// equal ℓ: UsageError naming --seed-file) and the seeds of a Cardan poincare
/// file of the same top (its section S = −sin q2 q̇2, each seed's phase
/// condition the factor of its piece: section_crossings.hpp), not the critical orbits.
PeriodicResult periodic_families(const PeriodicFlow& flow, const PeriodicRequest& r);

}  // namespace lgi::experiments
