#include "experiments/cli/cli.hpp"

#include <iostream>
#include <string>

#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/h5md_writer.hpp"
#include "lgi/build_info.hpp"

namespace lgi::experiments {
namespace {

std::string join_command_line(int argc, const char* const* argv) {
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

CommandLine::CommandLine(int argc, const char* const* argv)
    : argc_(argc),
      argv_(argv),
      app_("lgi: geometric (Lie-group) integration of rigid-body dynamics on SO(3) x R^3"),
      context_{join_command_line(argc, argv)} {
  app_.set_version_flag("--version", std::string(build_info::version));
  app_.require_subcommand(1);
  // One line per subcommand; each is declared in its own commands/<name>_command.cpp.
  subcommands_ = {
      add_simulate_subcommand(app_, context_),
      add_schemes_subcommand(app_),
      add_scenes_subcommand(app_),
      add_work_precision_subcommand(app_, context_),
      add_long_time_subcommand(app_, context_),
      add_singularity_subcommand(app_, context_),
      add_stress_subcommand(app_, context_),
      add_sweep_subcommand(app_, context_),
      add_equilibria_subcommand(app_, context_),
      add_bifurcation_subcommand(app_, context_),
      add_poincare_subcommand(app_, context_),
      add_region_subcommand(app_, context_),
      add_chaos_map_subcommand(app_, context_),
      add_actions_subcommand(app_, context_),
      add_indicators_subcommand(app_, context_),
      add_quantum_subcommand(app_, context_),
      add_periodic_subcommand(app_, context_),
  };
}

std::optional<int> CommandLine::parse(std::ostream& out, std::ostream& err) {
  selected_ = nullptr;
  try {
    app_.parse(argc_, argv_);
  } catch (const CLI::CallForHelp& e) {
    return app_.exit(e, out, err);
  } catch (const CLI::CallForAllHelp& e) {
    return app_.exit(e, out, err);
  } catch (const CLI::CallForVersion& e) {
    return app_.exit(e, out, err);
  } catch (const CLI::ParseError& e) {
    err << "lgi: " << one_line(e.what()) << " (see lgi --help)\n";
    return exit_bad_input;
  }
  for (const auto& sub : subcommands_)
    if (sub.app->parsed()) selected_ = &sub;
  if (selected_ == nullptr) return exit_bad_input;  // require_subcommand(1) makes this unreachable
  try {
    if (selected_->check) selected_->check();
  } catch (const InputError& e) {
    err << "lgi: " << one_line(e.what()) << '\n';
    return exit_bad_input;
  } catch (const UsageError& e) {
    err << "lgi: " << one_line(e.what()) << '\n';
    return exit_bad_input;
  }
  return std::nullopt;
}

int CommandLine::run(std::ostream& err) const {
  if (selected_ == nullptr) return exit_bad_input;
  try {
    return selected_->action();
  } catch (const InputError& e) {
    err << "lgi: " << one_line(e.what()) << '\n';
    return exit_bad_input;
  } catch (const UsageError& e) {
    err << "lgi: " << one_line(e.what()) << '\n';
    return exit_bad_input;
  } catch (const OutputFileError& e) {
    err << "lgi: " << one_line(e.what()) << '\n';
    return exit_bad_input;
  } catch (const RunError& e) {
    err << "lgi: " << one_line(e.what()) << '\n';
    return exit_run_failed;
  } catch (const std::exception& e) {
    err << "lgi: internal error: " << one_line(e.what()) << '\n';
    return exit_run_failed;
  }
}

int run_cli(int argc, char** argv) {
  CommandLine command_line(argc, argv);
  if (const std::optional<int> status = command_line.parse(std::cout, std::cerr)) return *status;
  return command_line.run(std::cerr);
}

}  // namespace lgi::experiments
