#pragma once
// The starts of `lgi periodic` other than the equilibria (experiments/PERIODIC.md):
// --seed-file (a point and a period guess a line) and --seeds-from-poincare
// (rows of a `lgi poincare` file's /events, or points (φ, ϑ, sheet) of its
// Richter section, or (x, y, piece) of a Cardan top's section, with the period
// guessed as the time of the N-th return to the section in the seed's direction).
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "experiments/analysis/periodic/section_crossings.hpp"
#include "experiments/io/poincare_file.hpp"

namespace lgi::experiments {

/// Seeds: one per line, Pi1 Pi2 Pi3 Gamma1 Gamma2 Gamma3 T (spaces or commas; '#' starts a comment).
std::vector<std::pair<Vec6, double>> read_seeds(const std::string& path);

struct SectionSeed {
  Vec6 x = Vec6::Zero();
  double period = 0.0;  // the guess; 0 if no return was found (failure says why)
  std::string label;    // "row 12", "point (phi, theta, sheet)"
  std::string failure;
  double h = NAN;       // the level of the orbit sought (NaN: H at x)
  int returns = 0;      // its own --poincare-point ...,N; 0: --returns
  std::optional<PhaseSection> section{};  // its phase condition (a Cardan top: the factor of its piece)
};

/// The section of a poincare file (kind and axis; a Cardan file's: cardan_factor 0).
PhaseSection section_of(const PoincareFile& f);

/// --poincare-rows "3,17,40" (rows of /events, from 0) and --poincare-point
/// "phi,theta,sheet[,N]" (each a point of Richter's section at the file's level;
/// on a Cardan top "x,y,piece" of its section, analysis/cardan_section.hpp),
/// each with its period guess after `returns` returns in its direction (N of
/// its own if given; integrated with step dt for at most t_max per `returns`).
/// UsageError naming the flag on a bad value; on a Cardan top also on a row whose
/// p1 or H (under `flow`) is not the file's l or h (another top's file).
std::vector<SectionSeed> poincare_seeds(const PeriodicFlow& flow, const PoincareFile& f, const std::string& rows,
                                        const std::vector<std::string>& points, int returns, double dt, double t_max);

}  // namespace lgi::experiments
