// Instantiations of the baselines in the matrix chart, for every stepper and model.
#include "integrators/baselines/matrix.hpp"

#include "integrators/baselines/baselines.hpp"

namespace lgi::integrators::baselines {

RunStats run_matrix(Stepper s, const system::AnyModel& model, State& state, const RunConfig& cfg, Observer& observer) {
  return run_with_stepper<MatrixCoordinates>(s, model, state, cfg, observer);
}

}  // namespace lgi::integrators::baselines
