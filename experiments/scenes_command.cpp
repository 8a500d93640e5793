// lgi scenes [DIR]: the scene files in a folder, their names and the
// invariants that apply to each.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <vector>

#include "experiments/commands.hpp"
#include "experiments/exit_status.hpp"
#include "experiments/input_error.hpp"
#include "experiments/scene_reader.hpp"
#include "integrators/system/invariants.hpp"

namespace lgi::experiments {

int scenes_command(const ScenesOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(options.directory, ec)) throw UsageError("DIR: '" + options.directory + "' is not a folder");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(options.directory, ec))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  int status = exit_ok;
  for (const auto& f : files) {
    try {
      const system::Scene scene = read_scene(f.string());
      const system::AnyModel model = system::make_model(scene);
      const system::SceneInvariants inv(scene, model);
      std::string names;
      for (const auto& n : inv.all_names()) names += (names.empty() ? "" : ", ") + n;
      std::cout << f.filename().string() << "\t" << scene.name << "\tinvariants: " << (names.empty() ? "none" : names)
                << '\n';
    } catch (const InputError& e) {
      std::cerr << "lgi: " << e.what() << '\n';
      status = exit_bad_input;
    }
  }
  return status;
}

}  // namespace lgi::experiments
