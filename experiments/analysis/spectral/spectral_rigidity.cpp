// The Dyson–Mehta Δ₃(L) (spectral_rigidity.hpp).
#include "experiments/analysis/spectral/spectral_rigidity.hpp"

#include <cmath>
#include <vector>

namespace lgi::experiments::spectral {

double delta3_window(std::span<const double> unfolded, double start, double length) {
  const LevelRange r = levels_in_window(unfolded, start, length);
  const double centre = start + 0.5 * length, n = static_cast<double>(r.last - r.first);
  double s1 = 0.0, s2 = 0.0, weighted = 0.0;
  for (std::size_t i = r.first; i < r.last; ++i) {
    const double e = unfolded[i] - centre, k = static_cast<double>(i - r.first + 1);
    s1 += e;
    s2 += e * e;
    weighted += (n - 2.0 * k + 1.0) * e;
  }
  const double l2 = length * length;
  return n * n / 16.0 - s1 * s1 / l2 + 1.5 * n * s2 / l2 - 3.0 * s2 * s2 / (l2 * l2) + weighted / length;
}

WindowStatistic spectral_rigidity(std::span<const double> unfolded, double length) {
  WindowStatistic out;
  out.length = length;
  const std::vector<StartSegment> segments = window_start_segments(unfolded, length);
  if (segments.empty()) return {length, NAN, NAN, 0};
  // 3-point Gauss–Legendre on [−1, 1]: exact for degree 5.
  const double node = std::sqrt(0.6), nodes[3] = {-node, 0.0, node}, weights[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double total = 0.0, integral = 0.0;
  for (const StartSegment& seg : segments) {
    const double mid = 0.5 * (seg.from + seg.to), half = 0.5 * (seg.to - seg.from);
    for (int q = 0; q < 3; ++q) integral += half * weights[q] * delta3_window(unfolded, mid + half * nodes[q], length);
    total += seg.to - seg.from;
  }
  out.value = integral / total;
  std::vector<double> samples;
  for (double x = unfolded.front(); x + length <= unfolded.back(); x += length)
    samples.push_back(delta3_window(unfolded, x, length));
  out.disjoint = samples.size();
  out.standard_error = sample_mean(samples).standard_error;
  return out;
}

}  // namespace lgi::experiments::spectral
