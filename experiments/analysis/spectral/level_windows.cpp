// Window starts over an unfolded spectrum (level_windows.hpp).
#include "experiments/analysis/spectral/level_windows.hpp"

#include <algorithm>
#include <cmath>

namespace lgi::experiments::spectral {

std::vector<StartSegment> window_start_segments(std::span<const double> unfolded, double length) {
  std::vector<StartSegment> segments;
  if (unfolded.empty() || !(length > 0)) return segments;
  const double a = unfolded.front(), b = unfolded.back() - length;
  if (!(b > a)) return segments;
  std::vector<double> cuts{a, b};
  for (double x : unfolded) {
    if (x > a && x < b) cuts.push_back(x);
    if (x - length > a && x - length < b) cuts.push_back(x - length);
  }
  std::sort(cuts.begin(), cuts.end());
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    if (cuts[i + 1] > cuts[i]) segments.push_back({cuts[i], cuts[i + 1]});
  return segments;
}

LevelRange levels_in_window(std::span<const double> unfolded, double start, double length) {
  const auto first = std::lower_bound(unfolded.begin(), unfolded.end(), start);
  const auto last = std::upper_bound(first, unfolded.end(), start + length);
  return {static_cast<std::size_t>(first - unfolded.begin()), static_cast<std::size_t>(last - unfolded.begin())};
}

SampleMean sample_mean(std::span<const double> values) {
  const double n = static_cast<double>(values.size());
  if (values.empty()) return {NAN, NAN};
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= n;
  if (values.size() < 2) return {mean, NAN};
  double ss = 0.0;
  for (double v : values) ss += (v - mean) * (v - mean);
  return {mean, std::sqrt(ss / (n - 1.0) / n)};
}

}  // namespace lgi::experiments::spectral
