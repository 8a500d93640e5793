#pragma once
// lgi poincare --seeds FILE: orbits started at chosen points instead of the
// level-set draw (experiments/POINCARE.md, "Seeds"). The file is a CSV with
// a header naming its columns, '#' lines ignored, in one of two forms:
//   phi,theta,sheet  a point of Richter's section at the level (l, h): Γ from
//                    (φ, ϑ) in the section frame (section_frame), Π the state
//                    on the section with Π·Γ = l, H = h and φ̇ of the sheet's sign;
//   gamma_1,gamma_2,gamma_3,angular_momentum_1,angular_momentum_2,angular_momentum_3
//                    a state (Γ, Π), which must lie on the level (l, h) to 1e-8.
// Anything else, a row off the level or with no state there (outside the
// accessible region U_l <= h), is a UsageError naming the file and the line.
#include <string>
#include <vector>

#include "experiments/analysis/poincare_section.hpp"

namespace lgi::experiments {

struct SeedState {
  Vec3 gamma = Vec3::UnitZ();
  Vec3 Pi = Vec3::Zero();
};

/// The state on Richter's section {(Γ × Ω)·e = 0} over Γ at the level (l, h)
/// with the sheet's sign of φ̇ (section_point): Π = Π0 + s n on the line of
/// the two linear conditions Π·Γ = l, Π·J⁻¹(e × Γ) = 0, s a root of H = h.
/// False where the line misses the level (Γ outside the accessible region)
/// or Γ = ±e (a pole of the section's coordinates).
bool section_state(const HeavyTopBody& body, const Vec3& e, double l, double h, const Vec3& gamma, int sheet,
                   Vec3& Pi);

/// Reads --seeds FILE (the forms above) for the section of axis e and kind at (l, h).
std::vector<SeedState> read_section_seeds(const std::string& path, const HeavyTopBody& body, SectionKind kind,
                                          const Vec3& e, double l, double h);

}  // namespace lgi::experiments
