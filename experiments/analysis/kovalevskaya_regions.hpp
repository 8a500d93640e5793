#pragma once
// The regions of the Kovalevskaya top's (h, k) plane at a leaf labelled by their
// number of Liouville tori: level sets sampled inside the attained range, away
// from the Appelrot families, and their components counted
// (level_set_components.hpp; experiments/EQUILIBRIA.md, "Region labels").
#include <functional>
#include <vector>

#include "experiments/analysis/kovalevskaya_diagram.hpp"

namespace lgi::experiments {

/// One sampled regular value (scaled h̃, k) at scaled ℓ̃ and its level set's components.
struct RegionSample {
  double h = 0.0, k = 0.0;
  int tori = 0;    // the count when resolved; −1 when the radii r and 2r disagree
  int points = 0;  // states on the level set
};

/// The range of k on the energy surface at one scaled energy h̃ (per component).
struct RangeAtEnergy {
  double h = 0.0;
  std::vector<KRange> components;
};

/// Samples at 8 fractions of each component's k range, at every `stride`-th energy of
/// `ranges`, skipping values within 3 % of the range of an Appelrot family.
/// `keep_going`, if given, is called before each level set; false stops: the samples so far.
std::vector<RegionSample> kovalevskaya_region_samples(const HeavyTopBody& scaled, double l_scaled,
                                                      const std::vector<RangeAtEnergy>& ranges, int stride, int seeds,
                                                      const std::function<bool()>& keep_going = {});

}  // namespace lgi::experiments
