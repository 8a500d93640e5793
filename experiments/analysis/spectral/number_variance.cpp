// The number variance Σ²(L) (number_variance.hpp).
#include "experiments/analysis/spectral/number_variance.hpp"

#include <cmath>
#include <vector>

namespace lgi::experiments::spectral {

WindowStatistic number_variance(std::span<const double> unfolded, double length) {
  WindowStatistic out;
  out.length = length;
  const std::vector<StartSegment> segments = window_start_segments(unfolded, length);
  if (segments.empty()) return {length, NAN, NAN, 0};
  double total = 0.0, sum_n = 0.0, sum_n2 = 0.0;
  for (const StartSegment& seg : segments) {
    const LevelRange r = levels_in_window(unfolded, 0.5 * (seg.from + seg.to), length);
    const double n = static_cast<double>(r.last - r.first), w = seg.to - seg.from;
    total += w;
    sum_n += w * n;
    sum_n2 += w * n * n;
  }
  const double mean_n = sum_n / total;
  out.value = sum_n2 / total - mean_n * mean_n;
  std::vector<double> samples;
  for (double x = unfolded.front(); x + length <= unfolded.back(); x += length) {
    const LevelRange r = levels_in_window(unfolded, x, length);
    const double d = static_cast<double>(r.last - r.first) - mean_n;
    samples.push_back(d * d);
  }
  out.disjoint = samples.size();
  out.standard_error = sample_mean(samples).standard_error;
  return out;
}

}  // namespace lgi::experiments::spectral
