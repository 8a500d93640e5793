#pragma once
// The scalar scheme behind the lanes of a scheme with memory (docs/ensemble.md).
// A kernel such as dmv_kernel.hpp takes only a scheme's common step in its
// lanes; where a lane needs anything else (the first steps of a run, a
// Newton solve that does not pass at once, a refusal), the ensemble stepper
// hands that lane's state and memory to the scalar scheme, which takes the
// step exactly as a run of that trajectory alone would, and writes them back.
// One scalar scheme object per lane holds the lane's per-run constants.
// Called outside the kernels, at most once per lane and step; compiled for
// the baseline instruction set only (dmv_fallback.hpp, instantiated by the
// registry for each scheme whose facts declare LaneKernel::dmv_diagonal).
#include <memory>
#include <span>

#include "integrators/ensemble/ensemble_model.hpp"
#include "integrators/core/scheme_interface.hpp"
#include "integrators/system/model.hpp"

namespace lgi::integrators::ensemble {

/// What one lane's step did: the scalar status and the work counters it adds
/// (as detail::recorded_step records them).
struct LaneOutcome {
  StepStatus status{};
  WorkCounters work{};
};

class LaneFallback {
 public:
  virtual ~LaneFallback() = default;
  /// The scheme's start() for the lane at s; writes the lane's memory rows and constants.
  virtual StepStatus start(int lane, const State& s, double t0, LaneMemory& memory) = 0;
  /// The scalar step of the lane from its state (block) and memory, both written back.
  virtual void step(int lane, LaneBlock& block, LaneMemory& memory, double t, double h, int retry_halving,
                    LaneOutcome& out) = 0;
  /// The lane's scheme with the memory `snapshot` (dmv_rows::memory values) stepping x (event location).
  virtual bool step_from(int lane, std::span<const double> snapshot, State& x, double t, double h, int retry_halving,
                         WorkCounters& work) = 0;
};

}  // namespace lgi::integrators::ensemble
