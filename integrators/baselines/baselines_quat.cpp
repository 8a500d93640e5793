// Instantiations of the quat and quat-normalized baselines, for every stepper and model.
#include "integrators/baselines/quaternion.hpp"

#include "integrators/baselines/baselines.hpp"

namespace lgi::integrators::baselines {

RunStats run_quat(bool normalized, Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg,
                  Observer& observer) {
  if (normalized) return run_with_stepper<QuatNormalizedCoordinates>(s, model, state, cfg, observer);
  return run_with_stepper<QuatCoordinates>(s, model, state, cfg, observer);
}

}  // namespace lgi::integrators::baselines
