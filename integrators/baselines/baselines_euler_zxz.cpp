// Instantiations of the baselines in the euler_zxz chart, for every stepper and model.
#include "integrators/baselines/euler_zxz.hpp"

#include "integrators/baselines/baselines.hpp"

namespace lgi::integrators::baselines {

RunStats run_euler_zxz(Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  return run_with_stepper<EulerZxzCoordinates>(s, model, state, cfg, observer);
}

}  // namespace lgi::integrators::baselines
