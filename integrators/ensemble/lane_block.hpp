#pragma once
// What every kernel returns (ensemble_model.hpp, StepKernel): whether each
// active lane of a LaneBlock is finite after the step and, for a scheme with
// memory, was stepped by the kernel. Computed in the lanes, so that in the
// common case the stepper reads no flag lane by lane.
#include "integrators/ensemble/ensemble_model.hpp"
#include "integrators/ensemble/lanes.hpp"

namespace lgi::integrators::ensemble {

/// Whether every active lane (dmv_rows::active) has a finite state (x − x is 0
/// for a finite x and NaN otherwise, as detail::finite_state) and `stepped`.
template <class T, class Mask>
inline bool active_lanes_clear(const LaneBlock& block, const LaneMemory& memory, const Mask& stepped) {
  using B = typename T::batch_type;
  constexpr int K = T::batches;
  T z(0.0);
  for (const auto& row : block.row) {
    const T x = load<B, K>(row);
    z = z + (x - x);
  }
  return all((stepped & equal(z, 0.0)) | equal(load<B, K>(memory.row[dmv_rows::active]), 0.0));
}

}  // namespace lgi::integrators::ensemble
