// Instantiations of the baselines in the rotvec chart, for every stepper and model.
#include "integrators/baselines/rotation_vector.hpp"

#include "integrators/baselines/baselines.hpp"

namespace lgi::integrators::baselines {

RunStats run_rotvec(Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  return run_with_stepper<RotationVectorCoordinates>(s, model, state, cfg, observer);
}

}  // namespace lgi::integrators::baselines
