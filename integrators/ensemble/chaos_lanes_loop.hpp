#pragma once
// The loop of the chaos indicators (integrators/core/tangent_flow.hpp,
// accumulate_chaos_indicators with ChaosAccumulator) in lanes, for any state
// space: the caller's `step(t, h)` advances each lane's state and tangent
// vector and returns |v| and z (z = 0 exactly where the state is finite,
// x − x being 0 only for a finite x); `scale(norm)` divides v by |v|. Then
// ln|v| from libm lane by lane, and λ's and MEGNO's sums updated with the
// same operations in the same order as the scalar loop (docs/ensemble.md,
// "Tangent flows in lanes"). The time grid (steps dt, the last one
// shortened) is common to all lanes, so its arithmetic is scalar here. A
// lane whose |v| is not finite or not positive, or whose state is not
// finite, stops running (the scalar loop returns NaN there); the others go
// on. SO(3) × ℝ³: chaos_kernel.hpp; T³ × ℝ³: cardan_tangent_kernel.hpp.
#include <cmath>
#include <cstdint>

#include "integrators/ensemble/lanes.hpp"
#include "integrators/ensemble/tangent_block.hpp"

namespace lgi::integrators::ensemble {

/// |v| and the finiteness sum z of one lane step (see above).
template <class T>
struct LaneStepNorm {
  T norm;
  T z;
};

/// Up to max_steps steps of the indicators' loop from c.t towards t_end.
template <class T, class Step, class Scale>
inline void chaos_lanes_loop(ChaosLanes& c, double t0, double t_end, double dt, std::int64_t max_steps, Step&& step,
                             Scale&& scale) {
  using B = typename T::batch_type;
  constexpr int K = T::batches;
  T log_sum = load<B, K>(c.log_sum), weighted = load<B, K>(c.weighted), mean_sum = load<B, K>(c.mean_sum);
  T y_last = load<B, K>(c.y), marked_log_sum = load<B, K>(c.marked_log_sum);
  T running = load<B, K>(c.running), steps = load<B, K>(c.steps);
  for (std::int64_t n = 0; n < max_steps && c.t < t_end; ++n) {
    const double t = c.t;
    const double h = (t_end - t) < 1.0000001 * dt ? t_end - t : dt;
    const LaneStepNorm<T> r = step(t, h);
    c.t = (t_end - t) < 1.0000001 * dt ? t_end : t + h;
    const auto good = equal(r.norm - r.norm, 0.0) & greater(r.norm, 0.0) & equal(r.z, 0.0);
    running = select(good, running, T(0.0));
    const auto idle = equal(running, 0.0);
    if (all(idle)) break;
    scale(r.norm);
    // ChaosAccumulator::add(s, h, |v|)
    const double s = c.t - t0;
    T d, unused;
    for_lanes_unless(idle, r.norm, d, unused, [](double in, double& out, double&) { out = std::log(in); });
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
  store(log_sum, c.log_sum), store(weighted, c.weighted), store(mean_sum, c.mean_sum);
  store(y_last, c.y), store(marked_log_sum, c.marked_log_sum), store(running, c.running), store(steps, c.steps);
}

}  // namespace lgi::integrators::ensemble
