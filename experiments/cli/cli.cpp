#include "experiments/cli/cli.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <vector>

#include "experiments/cli/commands.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/h5md_writer.hpp"
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

/// CLI11's messages can span lines; an lgi error is one line on stderr (README.md).
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
  const CommandContext context{join_command_line(argc, argv)};

  // One line per subcommand; each is declared in its own commands/<name>_command.cpp.
  const std::vector<Subcommand> subcommands = {
      add_simulate_subcommand(app, context),
      add_schemes_subcommand(app),
      add_scenes_subcommand(app),
      add_work_precision_subcommand(app, context),
      add_long_time_subcommand(app, context),
      add_singularity_subcommand(app, context),
      add_stress_subcommand(app, context),
      add_sweep_subcommand(app, context),
      add_equilibria_subcommand(app, context),
      add_bifurcation_subcommand(app, context),
      add_poincare_subcommand(app, context),
  };

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
    for (const auto& sub : subcommands)
      if (sub.app->parsed()) return sub.action();
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
