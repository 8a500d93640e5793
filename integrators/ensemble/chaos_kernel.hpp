#pragma once
// The loop of the chaos indicators (integrators/core/tangent_flow.hpp,
// accumulate_chaos_indicators with ChaosAccumulator) in lanes: each lane's
// state and tangent vector stepped by tangent_kernel.hpp, |v| summed in
// Eigen's order, v divided by it, ln|v| from libm lane by lane, and λ's and
// MEGNO's sums updated with the same operations in the same order as the
// scalar loop (docs/ensemble.md, "Tangent flows in lanes"). The time grid
// (steps dt, the last one shortened) is common to all lanes, so its
// arithmetic is scalar here. A lane whose |v| is not finite or not positive,
// or whose Π is not finite, stops running (the scalar loop returns NaN
// there); the others go on.
#include <cmath>
#include <cstdint>

#include "integrators/ensemble/tangent_kernel.hpp"

namespace lgi::integrators::ensemble {

/// ln x in the lanes where `skip` is false (0 elsewhere): libm's, lane by lane.
template <class B, int K>
inline Lanes<B, K> log_unless(const LaneMask<B, K>& skip, const Lanes<B, K>& x) {
  Lanes<B, K> y, unused;
  for_lanes_unless(skip, x, y, unused, [](double in, double& out, double&) { out = std::log(in); });
  return y;
}

/// Up to max_steps steps of the loop (ChaosKernel, tangent_block.hpp).
template <class T>
inline void chaos_block_run(const EnsembleModel& model, TangentBlock& block, ChaosLanes& c, double t0, double t_end,
                            double dt, std::int64_t max_steps) {
  using B = typename T::batch_type;
  constexpr int K = T::batches;
  M3<T> R;
  V3<T> Pi;
  Tangent6<T> v[1];
  tangent_detail::load_block(block, R, Pi, v);
  T log_sum = load<B, K>(c.log_sum), weighted = load<B, K>(c.weighted), mean_sum = load<B, K>(c.mean_sum);
  T y_last = load<B, K>(c.y), marked_log_sum = load<B, K>(c.marked_log_sum);
  T running = load<B, K>(c.running), steps = load<B, K>(c.steps);
  for (std::int64_t n = 0; n < max_steps && c.t < t_end; ++n) {
    const double t = c.t;
    const double h = (t_end - t) < 1.0000001 * dt ? t_end - t : dt;
    tangent_rk_step<1>(model, R, Pi, v, t, h);
    c.t = (t_end - t) < 1.0000001 * dt ? t_end : t + h;
    const T norm = eigen_norm6(v[0]);
    // As the scalar loop: |v| finite and positive, Π finite (x − x is 0 only for a finite x).
    const T z = (Pi.v[0] - Pi.v[0]) + (Pi.v[1] - Pi.v[1]) + (Pi.v[2] - Pi.v[2]);
    const auto good = equal(norm - norm, 0.0) & greater(norm, 0.0) & equal(z, 0.0);
    running = select(good, running, T(0.0));
    const auto idle = equal(running, 0.0);
    if (all(idle)) break;
    for (int i = 0; i < 3; ++i) {
      v[0].xi.v[i] = v[0].xi.v[i] / norm;
      v[0].dPi.v[i] = v[0].dPi.v[i] / norm;
    }
    // ChaosAccumulator::add(s, h, |v|)
    const double s = c.t - t0;
    const T d = log_unless(idle, norm);
    log_sum = log_sum + d;
    weighted = weighted + (s - 0.5 * h) * d;
    const T y = 2.0 * weighted / s;
    mean_sum = mean_sum + 0.5 * h * (y_last + y);
    y_last = y;
    c.s = s;
    steps = select(idle, steps, steps + 1.0);
    ++c.grid_steps;
    if (!c.marked && c.t - t0 >= 0.5 * (t_end - t0)) {  // ChaosAccumulator::mark
      marked_log_sum = log_sum;
      c.marked_s = c.s;
      c.marked = true;
    }
  }
  tangent_detail::store_block(R, Pi, v, block);
  store(log_sum, c.log_sum), store(weighted, c.weighted), store(mean_sum, c.mean_sum);
  store(y_last, c.y), store(marked_log_sum, c.marked_log_sum), store(running, c.running), store(steps, c.steps);
}

template <class T>
LGI_FLATTEN inline void chaos_block_run_flattened(const EnsembleModel& model, TangentBlock& block, ChaosLanes& c,
                                                  double t0, double t_end, double dt, std::int64_t max_steps) {
  chaos_block_run<T>(model, block, c, t0, t_end, dt, max_steps);
}

}  // namespace lgi::integrators::ensemble
