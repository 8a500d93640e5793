#pragma once
// Windows [x, x + L] over an unfolded spectrum x_0 <= … <= x_{n−1}, their
// starts x running over [x_0, x_{n−1} − L] (every window inside the spectrum).
// The levels inside a window change only where x passes a level (x = x_i, the
// level leaves) or x + L does (x = x_i − L, it enters): between consecutive
// such points, the segments here, the window holds the same levels, so an
// average over all starts is a sum over segments of exact integrals
// (docs/spectral_statistics.md §4). Disjoint windows (starts x_0 + kL) give
// independent-ish samples for a standard error.
#include <cstddef>
#include <span>
#include <vector>

namespace lgi::experiments::spectral {

/// An average over window starts, with the standard error from the
/// `disjoint` windows x_0 + kL (the standard deviation of the statistic over
/// them divided by √disjoint; NaN for fewer than 2). value NaN when the
/// spectrum is shorter than L or L <= 0.
struct WindowStatistic {
  double length = 0.0, value = 0.0, standard_error = 0.0;
  std::size_t disjoint = 0;
};

/// The segments [u, v] (u < v) of window starts holding a fixed set of levels,
/// covering [x_0, x_{n−1} − L]; empty if that interval is empty.
struct StartSegment {
  double from, to;
};
std::vector<StartSegment> window_start_segments(std::span<const double> unfolded, double length);

/// The levels in [x, x + L]: indices [first, last) into the sorted levels.
struct LevelRange {
  std::size_t first, last;
};
LevelRange levels_in_window(std::span<const double> unfolded, double start, double length);

/// The mean and its standard error over values (NaN error for fewer than 2).
struct SampleMean {
  double mean, standard_error;
};
SampleMean sample_mean(std::span<const double> values);

}  // namespace lgi::experiments::spectral
