#include "experiments/io/scenes_location.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "experiments/errors/exit_status.hpp"

namespace lgi::experiments {

std::string shipped_scenes_dir(const std::string& flag) {
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
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const fs::path& candidate : {exe.parent_path() / ".." / "share" / "lgi" / "scenes",
                                     exe.parent_path() / ".." / ".." / "experiments" / "scenes"}) {
      if (fs::is_directory(candidate, ec)) return fs::weakly_canonical(candidate, ec).string();
    }
  }
  throw UsageError("--scenes-dir: the shipped scenes were not found beside " + exe.string() +
                   " (share/lgi/scenes or experiments/scenes); give --scenes-dir DIR");
}

}  // namespace lgi::experiments
