#include "experiments/cli.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "experiments/commands.hpp"
#include "experiments/exit_status.hpp"
#include "experiments/h5md_writer.hpp"
#include "experiments/input_error.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

std::string join_command_line(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) {
    if (i) s += ' ';
    s += argv[i];
  }
  return s;
}

/// CLI11's messages can span lines; cli.md wants one.
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{"lgi: geometric (Lie-group) integration of rigid-body dynamics on SO(3) x R^3"};
  app.set_version_flag("--version", std::string(build_info::version));
  app.require_subcommand(1);

  SimulateOptions sim;
  auto* simulate = app.add_subcommand("simulate", "Integrate one scene with one scheme and write an H5MD trajectory");
  simulate->add_option("--scene", sim.scene, "Scene file (TOML)")->required();
  simulate->add_option("--scheme", sim.scheme, "Scheme name (see `lgi schemes`)")->required();
  simulate->add_option("--dt", sim.dt, "Step size (fixed-step schemes; first trial step of adaptive ones). Default: the scene's [run] dt");
  simulate->add_option("--tol", sim.tol, "Tolerance of adaptive schemes. Default: the scene's [run] tol");
  simulate->add_option("--t-end", sim.t_end, "Final time. Default: the scene's [run] t_end");
  simulate->add_option("--save-every", sim.save_every, "Save every N steps; the initial and final states are always saved")
      ->capture_default_str();
  simulate->add_option("--out", sim.out, "Output trajectory file (HDF5, H5MD layout)")->required();
  simulate->add_flag("--force", sim.force, "Overwrite an existing output file");
  simulate->add_flag("--quiet", sim.quiet, "Print nothing but errors");

  SchemesOptions schemes_opt;
  auto* schemes = app.add_subcommand("schemes", "List every registered scheme with its order and properties");
  schemes->add_flag("--json", schemes_opt.json, "Machine-readable JSON");

  ScenesOptions scenes_opt;
  scenes_opt.directory = LGI_SCENES_DIR;
  auto* scenes = app.add_subcommand("scenes", "List the scene files in a folder and the invariants that apply");
  scenes->add_option("DIR", scenes_opt.directory, "Folder of scene files")->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "lgi: " << one_line(e.what()) << " (see lgi --help)\n";
    return exit_bad_input;
  }

  try {
    if (*simulate) {
      sim.command_line = join_command_line(argc, argv);
      return simulate_command(sim);
    }
    if (*schemes) return schemes_command(schemes_opt);
    if (*scenes) return scenes_command(scenes_opt);
  } catch (const InputError& e) {
    std::cerr << "lgi: " << one_line(e.what()) << '\n';
    return exit_bad_input;
  } catch (const UsageError& e) {
    std::cerr << "lgi: " << one_line(e.what()) << '\n';
    return exit_bad_input;
  } catch (const OutputFileError& e) {
    std::cerr << "lgi: " << one_line(e.what()) << '\n';
    return exit_bad_input;
  } catch (const RunError& e) {
    std::cerr << "lgi: " << one_line(e.what()) << '\n';
    return exit_run_failed;
  } catch (const std::exception& e) {
    std::cerr << "lgi: internal error: " << one_line(e.what()) << '\n';
    return exit_run_failed;
  }
  return exit_bad_input;
}

}  // namespace lgi::experiments
