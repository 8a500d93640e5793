#include "experiments/cli/cli.hpp"

#include <iostream>
#include <string>

#include "experiments/cli/argument_checks.hpp"
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

/// A refusal: one line "lgi: <what>" on `err`, and the exit status it ends with.
int refuse(std::ostream& err, const std::exception& e, int status) {
  err << "lgi: " << one_line(e.what()) << '\n';
  return status;
}

}  // namespace

CommandLine::CommandLine(int argc, const char* const* argv, const std::vector<CommandFactory>& commands)
    : argc_(argc),
      argv_(argv),
      app_("lgi: geometric (Lie-group) integration of rigid-body dynamics on SO(3) x R^3"),
      context_{join_command_line(argc, argv)} {
  app_.set_version_flag("--version", std::string(build_info::version));
  app_.require_subcommand(1);
  for (const CommandFactory add : commands) subcommands_.push_back(add(app_, context_));
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
    if (const std::string unknown = unknown_leading_argument(app_, argc_, argv_); !unknown.empty()) {
      err << unknown << '\n';
      return exit_bad_input;
    }
    err << "lgi: " << one_line(e.what()) << " (see lgi --help)\n";
    return exit_bad_input;
  }
  for (const auto& sub : subcommands_)
    if (sub.app->parsed()) selected_ = &sub;
  if (selected_ == nullptr) return exit_bad_input;  // require_subcommand(1) makes this unreachable
  try {
    check_argument_values(*selected_->app, argc_, argv_);
    if (selected_->check) selected_->check();
  } catch (const InputError& e) {
    return refuse(err, e, exit_bad_input);
  } catch (const UsageError& e) {
    return refuse(err, e, exit_bad_input);
  }
  return std::nullopt;
}

int CommandLine::run(std::ostream& err) const {
  if (selected_ == nullptr) return exit_bad_input;
  try {
    return selected_->action();
  } catch (const InputError& e) {
    return refuse(err, e, exit_bad_input);
  } catch (const UsageError& e) {
    return refuse(err, e, exit_bad_input);
  } catch (const OutputWriteError& e) {  // the output existed: a failed run, its .partial kept (README)
    return refuse(err, e, exit_run_failed);
  } catch (const OutputFileError& e) {
    return refuse(err, e, exit_bad_input);
  } catch (const RunError& e) {
    return refuse(err, e, exit_run_failed);
  } catch (const std::exception& e) {
    err << "lgi: internal error: " << one_line(e.what()) << '\n';
    return exit_run_failed;
  }
}

int run_cli(int argc, char** argv, const std::vector<CommandFactory>& commands) {
  CommandLine command_line(argc, argv, commands);
  if (const std::optional<int> status = command_line.parse(std::cout, std::cerr)) return *status;
  return command_line.run(std::cerr);
}

}  // namespace lgi::experiments
