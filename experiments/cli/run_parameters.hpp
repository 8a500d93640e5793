#pragma once
// The /parameters record of a run (OUTPUT.md for trajectories, RESULTS.md for
// result files): which scene and scheme, with which step, as asked for on
// which command line. Kept in one place so that every subcommand records a
// run the same way; the writers add the build provenance themselves
// (compiler, cxx_flags, build_type, hdf5_version, utc_start).
#include <string>

#include "experiments/io/results_file.hpp"  // ResultAttributes
#include "integrators/registry/registry.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments {

/// scene_file, scene_name and scene_toml (the full scene text).
ResultAttributes scene_parameters(const system::Scene& scene);

/// scene_parameters() plus scheme and command_line; tol (and dt, the first
/// trial step, when one was given) for an adaptive scheme, dt for a
/// fixed-step one; t_end.
ResultAttributes run_parameters(const system::Scene& scene, const integrators::SchemeInfo& scheme,
                                const integrators::RunConfig& cfg, const std::string& command_line);

}  // namespace lgi::experiments
