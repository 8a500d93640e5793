// Region labels of the Kovalevskaya (h, k) diagram (kovalevskaya_regions.hpp).
#include "experiments/analysis/kovalevskaya_regions.hpp"

#include <algorithm>
#include <cmath>

#include "experiments/analysis/kovalevskaya_critical.hpp"
#include "experiments/analysis/level_set_components.hpp"

namespace lgi::experiments {

std::vector<RegionSample> kovalevskaya_region_samples(const HeavyTopBody& scaled, double l_scaled,
                                                      const std::vector<RangeAtEnergy>& ranges, int stride, int seeds,
                                                      const std::function<bool()>& keep_going) {
  const SecondIntegral K = kovalevskaya_integral(scaled);
  std::vector<RegionSample> out;
  for (std::size_t i = 0; i < ranges.size(); i += static_cast<std::size_t>(std::max(1, stride))) {
    const double h = ranges[i].h;
    for (const KRange& c : ranges[i].components) {
      const double span = c.k_max - c.k_min;
      if (!(span > 0.0)) continue;
      for (int j = 0; j < 8; ++j) {
        const double k = c.k_min + span * (j + 0.5) / 8.0;
        if (appelrot_distance(l_scaled, h, k).distance < 0.03 * span) continue;  // too near a critical arc
        if (keep_going && !keep_going()) return out;
        const LevelSetComponents n = level_set_components(scaled, l_scaled, h, k, K, seeds);
        if (n.points == 0) continue;
        out.push_back({h, k, n.resolved() ? n.components : -1, n.points});
      }
    }
  }
  return out;
}

}  // namespace lgi::experiments
