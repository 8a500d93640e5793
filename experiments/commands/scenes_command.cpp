// lgi scenes [DIR]: the scene files in a folder, their names and the
// invariants that apply to each.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <vector>

#include "experiments/commands/all_commands.hpp"
#include "experiments/io/scenes_location.hpp"
#include <memory>
#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/input_file.hpp"
#include "experiments/io/scene_reader.hpp"
#include "integrators/system/invariants.hpp"

namespace lgi::experiments {
namespace {

int list_scenes(const std::string& directory) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) throw UsageError("DIR: '" + directory + "' is not a folder");
  const std::vector<fs::path> files = scene_files(directory);
  int status = exit_ok;
  for (const auto& f : files) {
    try {
      // A listing never waits on a FIFO named *.toml (input_file.hpp): only regular files are read.
      if (const std::string why = regular_file_problem(f.string()); !why.empty())
        throw InputError(f.string() + ": cannot read scene file: " + why);
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

}  // namespace

Subcommand add_scenes_subcommand(CLI::App& app, const CommandContext& /*context*/) {
  auto directory = std::make_shared<std::string>();
  auto* sub = app.add_subcommand("scenes", "List the scene files in a folder and the invariants that apply");
  sub->add_option("DIR", *directory,
                  "Folder of scene files. Default: the shipped scenes (--scenes-dir rules: LGI_SCENES_DIR, else "
                  "beside the lgi executable)");
  return {sub, [directory] { return list_scenes(shipped_scenes_dir(*directory)); }};
}

}  // namespace lgi::experiments
