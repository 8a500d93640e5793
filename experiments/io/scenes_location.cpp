#include "experiments/io/scenes_location.hpp"

#include <algorithm>
#include <cstdlib>
#include <system_error>

#include "experiments/errors/exit_status.hpp"

namespace lgi::experiments {

std::string shipped_scenes_dir(const std::string& flag) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return shipped_scenes_dir(flag, ec ? fs::path() : exe,
                            {fs::path("..") / "share" / "lgi" / "scenes", fs::path("..") / ".." / "experiments" / "scenes"});
}

std::string shipped_scenes_dir(const std::string& flag, const std::filesystem::path& binary,
                               const std::vector<std::filesystem::path>& relative_candidates) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!flag.empty()) {
    if (!fs::is_directory(flag, ec)) throw UsageError("--scenes-dir: '" + flag + "' is not a folder");
    return flag;
  }
  if (const char* env = std::getenv("LGI_SCENES_DIR"); env && *env) {
    if (!fs::is_directory(env, ec))
      throw UsageError(std::string("--scenes-dir: the environment's LGI_SCENES_DIR '") + env + "' is not a folder");
    return env;
  }
  if (!binary.empty()) {
    for (const fs::path& relative : relative_candidates) {
      const fs::path candidate = binary.parent_path() / relative;
      if (fs::is_directory(candidate, ec)) return fs::weakly_canonical(candidate, ec).string();
    }
  }
  throw UsageError("--scenes-dir: the shipped scenes were not found beside " + binary.string() +
                   " (share/lgi/scenes or experiments/scenes); give --scenes-dir DIR");
}

std::vector<std::filesystem::path> scene_files(const std::string& directory) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(directory, ec))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace lgi::experiments
