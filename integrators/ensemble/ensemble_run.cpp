// run_ensemble (ensemble_loop.hpp): the ensemble loop for the scalar scheme
// an EnsembleStepper steps as, instantiated by the registry for that scheme
// (SchemeInfo::lanes, lane_mode_of.hpp) and dispatched there on the model.
#include <stdexcept>
#include <string>

#include "integrators/ensemble/ensemble_loop.hpp"

namespace lgi::integrators::ensemble {

void run_ensemble(EnsembleStepper& e, const system::AnyModel& model, std::span<State> states, const RunConfig& cfg,
                  std::span<Observer* const> observers, std::span<RunStats> stats, EnsembleWorkspace& ws) {
  if (states.size() > static_cast<std::size_t>(e.lanes()) || observers.size() != states.size() ||
      stats.size() != states.size())
    throw std::invalid_argument("run_ensemble: at most lanes() states, one observer and one RunStats each");
  e.run_lanes()(e, model, states, cfg, observers, stats, ws);
}

}  // namespace lgi::integrators::ensemble
