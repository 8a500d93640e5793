#pragma once
// Where the shipped scenes are, for the subcommands that read them (scenes,
// stress, singularity) and for the Python module (python/): never a path
// compiled in from the source tree, so an installed or relocated lgi finds its own.
#include <filesystem>
#include <string>
#include <vector>

namespace lgi::experiments {

/// The scenes folder: `flag` (--scenes-dir) if not empty; else the
/// environment variable LGI_SCENES_DIR; else the first that exists of
/// <exe>/../share/lgi/scenes (an installed lgi, bin/lgi) and
/// <exe>/../../experiments/scenes (the build tree, build/<preset>/lgi).
/// Throws UsageError naming --scenes-dir when none is found.
std::string shipped_scenes_dir(const std::string& flag);

/// The same rules for another binary (the Python extension): the candidates
/// are folders relative to the folder of `binary`, tried in order.
std::string shipped_scenes_dir(const std::string& flag, const std::filesystem::path& binary,
                               const std::vector<std::filesystem::path>& relative_candidates);

/// The scene files (*.toml) of a folder, sorted by name.
std::vector<std::filesystem::path> scene_files(const std::string& directory);

}  // namespace lgi::experiments
