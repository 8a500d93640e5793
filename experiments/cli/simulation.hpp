#pragma once
// One run of `lgi simulate`, shared by the command (commands/simulate_command.cpp)
// and the Python module's lgi.simulate (python/): the checks of the run
// settings, the scheme's support of the scene, the /parameters record, the
// observer and writer, the statistics and the message of a failed run. The
// caller reads the scene and looks the scheme up.
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>

#include "experiments/io/h5md_writer.hpp"
#include "experiments/io/trajectory_observer.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// The settings of one run, as `lgi simulate` takes them (unset: the scene's [run]).
struct SimulationRequest {
  std::optional<double> dt, tol, t_end;
  std::int64_t save_every = 1;
  int retry_halving = 0;
  std::string out;  // empty: no file
  bool force = false;
  bool quiet = true;  // no warning about a large file
  std::string command_line;
  /// Samples at t0, t0 + D, …, t_end instead of every save_every-th step (cli/output_grid.hpp).
  std::optional<double> output_dt{};
};

/// The checks of the request that need no scene (flag ranges, --retry-halving
/// with an adaptive scheme, --output-dt with --save-every); throws UsageError
/// naming the flag.
void check_simulation_flags(const SimulationRequest& request, const integrators::SchemeInfo& scheme);

/// Validates the request against the scene and the scheme and fills the run
/// config (the request, then the scene's [run], step_settings.hpp). Throws
/// UsageError naming the flag.
integrators::RunConfig simulation_config(const SimulationRequest& request, const system::Scene& scene,
                                         const integrators::SchemeInfo& scheme);

/// Throws RunError ("<why>; scene <file> is not one") when the scheme cannot run on the scene.
void check_scheme_supports(const integrators::SchemeInfo& scheme, const system::Scene& scene,
                           const system::AnyModel& model);

struct SimulationOutcome {
  integrators::RunStats stats;
  Diagnostics diagnostics;      // as written to /diagnostics
  std::string error_summary;    // TrajectoryObserver::invariant_error_summary()
  std::string failure_message;  // empty if ok, else the line lgi prints after "lgi: "
};

/// Ends a run that has its stats and diagnostics: a failed run gets its
/// message ("<scheme> on <scene file>: <status>") and its writer abandoned
/// (the .partial kept and named), a run that succeeded its writer finished.
/// `writer` may be null (no output file).
void close_simulation(SimulationOutcome& outcome, const std::string& scheme_name, const std::string& scene_file,
                      TrajectoryWriter* writer);

/// Runs the scheme from the scene's initial state with `cfg` (from
/// simulation_config), writing request.out if not empty and handing every
/// sample to `sink` if not null. `stop` is RunConfig::stop (may be null). A
/// failed run leaves <out>.partial and returns its message; the returned
/// outcome is never an exception for a failed run.
SimulationOutcome run_simulation(const system::Scene& scene, const integrators::SchemeInfo& scheme,
                                 const integrators::RunConfig& cfg, const SimulationRequest& request,
                                 SampleSink* sink, const std::atomic<bool>* stop);

}  // namespace lgi::experiments
