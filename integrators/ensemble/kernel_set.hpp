#pragma once
// The kernels of one instruction set, for ensemble_<isa>.cpp: each of those
// units includes this with its own lane type (docs/ensemble.md).
#include "integrators/ensemble/chaos_kernel.hpp"
#include "integrators/ensemble/dmv_kernel.hpp"
#include "integrators/ensemble/rkmk_kernel.hpp"
#include "integrators/tableaus/runge_kutta.hpp"

namespace lgi::integrators::ensemble {

template <class LaneType>
KernelSet kernel_set(const char* isa) {
  KernelSet set;
  set.isa = isa;
  set.lanes = LaneType::size;
  // Flattened where a batch holds 4 or more doubles (rkmk_kernel.hpp).
  if constexpr (LaneType::batch_type::size >= 4)
    set.rkmk4 = &rkmk_block_step_flattened<tableaus::classical_rk4, LaneType>;
  else
    set.rkmk4 = &rkmk_block_step<tableaus::classical_rk4, LaneType>;
  set.dmv_pre = &dmv_pre_block_step<LaneType>;
  return set;
}

/// The tangent-flow kernels (tangent_kernel.hpp, chaos_kernel.hpp), flattened as rkmk4's.
template <class LaneType>
TangentKernelSet tangent_kernel_set() {
  TangentKernelSet set;
  set.lanes = LaneType::size;
  if constexpr (LaneType::batch_type::size >= 4) {
    set.step_one = &tangent_block_step_flattened<1, LaneType>;
    set.step_six = &tangent_block_step_flattened<6, LaneType>;
    set.chaos = &chaos_block_run_flattened<LaneType>;
  } else {
    set.step_one = &tangent_block_step<1, LaneType>;
    set.step_six = &tangent_block_step<6, LaneType>;
    set.chaos = &chaos_block_run<LaneType>;
  }
  return set;
}

}  // namespace lgi::integrators::ensemble
