#pragma once
// The loops that advance a state with six tangent vectors on the fixed step
// grid of integrators::accumulate_chaos_indicators (steps dt, the last one
// shortened to land on T), for any tangent flow: `step(t, h, V)` advances
// the state and the columns of V from t by h, `finite()` says whether the
// state is still finite. SO(3) scenes step with integrators/core/tangent_flow.hpp,
// Cardan scenes with integrators/core/torus_tangent_flow.hpp.
//  - spectrum_loop: the Lyapunov spectrum, V re-orthonormalised by modified
//    Gram–Schmidt after every step (Benettin et al. 1980; chaos_indicators.hpp);
//  - gali_loop: GALI_k, each column normalised after every step, the indices
//    recorded at the sample times (gali.hpp).
// Both end with NaN values if the state or a vector blows up or `stop` is set
// (read every 256 steps: Ctrl-C).
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "experiments/analysis/gali.hpp"
#include "integrators/core/tangent_flow.hpp"

namespace lgi::experiments {

/// The size of the step from t towards t_end, and the time after it (exactly t_end at the end).
inline double grid_step(double t, double t_end, double dt) { return (t_end - t) < 1.0000001 * dt ? t_end - t : dt; }
inline double grid_next(double t, double t_end, double dt, double h) {
  return (t_end - t) < 1.0000001 * dt ? t_end : t + h;
}

/// Modified Gram–Schmidt on the columns of V in place; adds ln R_kk to sums.
/// False if a column vanished or is not finite.
inline bool orthonormalise(integrators::Mat6& V, std::array<double, 6>& sums) {
  for (int k = 0; k < 6; ++k) {
    for (int j = 0; j < k; ++j) V.col(k) -= V.col(j).dot(V.col(k)) * V.col(j);
    const double n = V.col(k).norm();
    if (!std::isfinite(n) || !(n > 0.0)) return false;
    V.col(k) /= n;
    sums[static_cast<std::size_t>(k)] += std::log(n);
  }
  return true;
}

/// The six exponents over [0, t_end] from the vectors V (columns, orthonormal).
template <class Step, class Finite>
std::array<double, 6> spectrum_loop(Step&& step, Finite&& finite, integrators::Mat6 V, double t_end, double dt,
                                    const std::atomic<bool>* stop) {
  std::array<double, 6> sums{};
  double t = 0.0;
  std::int64_t steps = 0;
  while (t < t_end) {
    if (++steps % 256 == 0 && stop != nullptr && stop->load(std::memory_order_relaxed)) {
      sums.fill(std::nan(""));
      return sums;
    }
    const double h = grid_step(t, t_end, dt);
    step(t, h, V);
    t = grid_next(t, t_end, dt, h);
    if (!orthonormalise(V, sums) || !finite()) {
      sums.fill(std::nan(""));
      return sums;
    }
  }
  for (double& s : sums) s /= t_end;
  return sums;
}

/// Normalises every column of V to 1; false if one vanished or is not finite.
inline bool normalise_columns(integrators::Mat6& V) {
  for (int k = 0; k < 6; ++k) {
    const double n = V.col(k).norm();
    if (!std::isfinite(n) || !(n > 0.0)) return false;
    V.col(k) /= n;
  }
  return true;
}

/// The times at which gali_loop records: the end of the first step at or
/// after each target (to 1e-7 dt) (gali_targets: increasing, the last = t_end), a step
/// recorded once; the same doubles as the loop's t. It walks the whole step grid (10^9
/// steps are seconds), so it reads `stop` every 2^20 steps: once set, the times so far.
inline std::vector<double> gali_times(const std::vector<double>& targets, double t_end, double dt,
                                      const std::atomic<bool>* stop = nullptr) {
  std::vector<double> times;
  double t = 0.0;
  std::size_t next = 0;
  std::int64_t steps = 0;
  while (t < t_end && next < targets.size()) {
    if (++steps % (std::int64_t{1} << 20) == 0 && stop != nullptr && stop->load(std::memory_order_relaxed)) break;
    t = grid_next(t, t_end, dt, grid_step(t, t_end, dt));
    const double slack = 1e-7 * dt;  // t sums steps: 2.9999999 is the step at 3
    if (t >= targets[next] - slack) times.push_back(t);
    while (next < targets.size() && targets[next] - slack <= t) ++next;
  }
  return times;
}

/// GALI_k (k = 2 … 6) of the deviation vectors V (columns) at `times`
/// (gali_times, ending at t_end); from a blow-up or `stop` on, the rows are NaN.
template <class Step, class Finite>
GaliCurves gali_loop(Step&& step, Finite&& finite, integrators::Mat6 V, const std::vector<double>& times,
                     double t_end, double dt, const std::atomic<bool>* stop) {
  GaliCurves out;
  out.t = times;
  GaliValues nan{};
  nan.fill(std::nan(""));
  out.log10_gali.assign(times.size(), nan);
  if (!normalise_columns(V)) return out;
  double t = 0.0;
  std::size_t next = 0;
  std::int64_t steps = 0;
  while (t < t_end && next < times.size()) {
    if (++steps % 256 == 0 && stop != nullptr && stop->load(std::memory_order_relaxed)) return out;
    const double h = grid_step(t, t_end, dt);
    step(t, h, V);
    t = grid_next(t, t_end, dt, h);
    if (!normalise_columns(V) || !finite()) return out;
    if (t == times[next]) out.log10_gali[next++] = log10_gali(V);
  }
  return out;
}

}  // namespace lgi::experiments
