#pragma once
// A registry entry's lane mode (docs/ensemble.md): what the ensemble needs of
// a scheme whose facts declare a lane kernel (SchemeFacts::lane_kernel),
// built by the registry from the scheme's type (lane_mode_of.hpp) so that the
// ensemble keeps no table of scheme names. Declarations only: registry.hpp
// includes this, and none of the ensemble's machinery.
#include <memory>
#include <span>

#include "integrators/core/run_config.hpp"
#include "integrators/core/scheme_facts.hpp"
#include "integrators/system/model.hpp"

namespace lgi::integrators {

namespace ensemble {

class EnsembleStepper;
class LaneFallback;
struct EnsembleModel;
struct EnsembleWorkspace;

/// The scalar scheme behind each lane of a kernel that leaves steps to it
/// (LaneKernel::dmv_diagonal, lane_fallback.hpp); sets the kernel's per-run
/// constants in `constants`.
using LaneFallbackFactory = std::unique_ptr<LaneFallback> (*)(const system::FreeBody& model,
                                                              EnsembleModel& constants);
/// The ensemble loop (ensemble_loop.hpp) with the scheme's scalar hooks, on the model's alternative.
using RunLanes = void (*)(EnsembleStepper& e, const system::AnyModel& model, std::span<system::State> states,
                          const RunConfig& cfg, std::span<Observer* const> observers, std::span<RunStats> stats,
                          EnsembleWorkspace& ws);

}  // namespace ensemble

/// What SchemeInfo holds of a scheme's lane kernel: none, or the kernel, the
/// ensemble loop for the scheme and, for a kernel that needs it, the scalar
/// scheme behind each lane.
struct LaneMode {
  LaneKernel kernel = LaneKernel::none;
  ensemble::RunLanes run = nullptr;
  ensemble::LaneFallbackFactory fallback = nullptr;
};

/// "rkmk4", "dmv-diagonal", or "" for none (`lgi schemes --json` "lane_kernel").
inline const char* lane_kernel_name(LaneKernel k) {
  switch (k) {
    case LaneKernel::rkmk4: return "rkmk4";
    case LaneKernel::dmv_diagonal: return "dmv-diagonal";
    case LaneKernel::none: break;
  }
  return "";
}

}  // namespace lgi::integrators
