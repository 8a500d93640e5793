#pragma once
// Where the shipped scenes are, for the subcommands that read them (scenes,
// stress, singularity): never a path compiled in from the source tree, so an
// installed or relocated lgi finds its own.
#include <string>

namespace lgi::experiments {

/// The scenes folder: `flag` (--scenes-dir) if not empty; else the
/// environment variable LGI_SCENES_DIR; else the first that exists of
/// <exe>/../share/lgi/scenes (an installed lgi, bin/lgi) and
/// <exe>/../../experiments/scenes (the build tree, build/<preset>/lgi).
/// Throws UsageError naming --scenes-dir when none is found.
std::string shipped_scenes_dir(const std::string& flag);

}  // namespace lgi::experiments
