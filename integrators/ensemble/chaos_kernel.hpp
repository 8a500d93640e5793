#pragma once
// The loop of the chaos indicators on SO(3) × ℝ³ in lanes: the loop of
// chaos_lanes_loop.hpp with each lane's state and tangent vector stepped by
// tangent_kernel.hpp and |v| summed in Eigen's order (docs/ensemble.md,
// "Tangent flows in lanes").
#include <cstdint>

#include "integrators/ensemble/chaos_lanes_loop.hpp"
#include "integrators/ensemble/tangent_kernel.hpp"

namespace lgi::integrators::ensemble {

/// Up to max_steps steps of the loop (ChaosKernel, tangent_block.hpp).
template <class T>
inline void chaos_block_run(const EnsembleModel& model, TangentBlock& block, ChaosLanes& c, double t0, double t_end,
                            double dt, std::int64_t max_steps) {
  M3<T> R;
  V3<T> Pi;
  Tangent6<T> v[1];
  tangent_detail::load_block(block, R, Pi, v);
  chaos_lanes_loop<T>(
      c, t0, t_end, dt, max_steps,
      [&](double t, double h) {
        tangent_rk_step<1>(model, R, Pi, v, t, h);
        // Π finite: x − x is 0 only for a finite x.
        return LaneStepNorm<T>{eigen_norm6(v[0]), (Pi.v[0] - Pi.v[0]) + (Pi.v[1] - Pi.v[1]) + (Pi.v[2] - Pi.v[2])};
      },
      [&](const T& norm) {
        for (int i = 0; i < 3; ++i) {
          v[0].xi.v[i] = v[0].xi.v[i] / norm;
          v[0].dPi.v[i] = v[0].dPi.v[i] / norm;
        }
      });
  tangent_detail::store_block(R, Pi, v, block);
}

template <class T>
LGI_FLATTEN inline void chaos_block_run_flattened(const EnsembleModel& model, TangentBlock& block, ChaosLanes& c,
                                                  double t0, double t_end, double dt, std::int64_t max_steps) {
  chaos_block_run<T>(model, block, c, t0, t_end, dt, max_steps);
}

}  // namespace lgi::integrators::ensemble
