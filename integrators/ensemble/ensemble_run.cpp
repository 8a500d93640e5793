// run_ensemble (ensemble_loop.hpp): the ensemble loop for the scalar scheme
// an EnsembleStepper steps as, dispatched once per run on the model.
#include <stdexcept>
#include <string>
#include <variant>

#include "integrators/ensemble/ensemble_loop.hpp"
#include "integrators/moser_veselov_preprocessed.hpp"
#include "integrators/rkmk.hpp"

namespace lgi::integrators::ensemble {

namespace {

template <class Scheme>
void run_with(EnsembleStepper& e, const system::AnyModel& model, std::span<State> states, const RunConfig& cfg,
              std::span<Observer* const> observers, std::span<RunStats> stats, EnsembleWorkspace& ws) {
  std::visit([&](const auto& m) { integrate_fixed_ensemble<Scheme>(e, m, states, cfg, observers, stats, ws); }, model);
}

}  // namespace

void run_ensemble(EnsembleStepper& e, const system::AnyModel& model, std::span<State> states, const RunConfig& cfg,
                  std::span<Observer* const> observers, std::span<RunStats> stats, EnsembleWorkspace& ws) {
  if (states.size() > static_cast<std::size_t>(e.lanes()) || observers.size() != states.size() ||
      stats.size() != states.size())
    throw std::invalid_argument("run_ensemble: at most lanes() states, one observer and one RunStats each");
  if (e.scheme() == "rkmk4") return run_with<Rkmk4>(e, model, states, cfg, observers, stats, ws);
  if (e.scheme() == "dmv") return run_with<Dmv>(e, model, states, cfg, observers, stats, ws);
  if (e.scheme() == "lgvi") return run_with<Lgvi>(e, model, states, cfg, observers, stats, ws);
  if (e.scheme() == "dmv-pre4") return run_with<DmvPre4>(e, model, states, cfg, observers, stats, ws);
  if (e.scheme() == "dmv-pre6") return run_with<DmvPre6>(e, model, states, cfg, observers, stats, ws);
  if (e.scheme() == "dmv-pre8") return run_with<DmvPre8>(e, model, states, cfg, observers, stats, ws);
  if (e.scheme() == "dmv-pre10") return run_with<DmvPre10>(e, model, states, cfg, observers, stats, ws);
  throw std::invalid_argument("run_ensemble: no scalar scheme for " + std::string(e.scheme()));
}

}  // namespace lgi::integrators::ensemble
