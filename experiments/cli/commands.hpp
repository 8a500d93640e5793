#pragma once
// The shape of a subcommand of `lgi`. Each lives in its own commands/<name>_command.cpp
// and registers itself on the CLI11 app with add_<name>_subcommand(), which
// declares its options and returns the action to run when it is selected. The
// table of them is built above this layer (commands/all_commands.hpp) and handed
// to the command line (cli.hpp): cli/ calls nothing in commands/.
// Actions return an exit status (exit_status.hpp) and throw InputError /
// UsageError / OutputFileError for bad input (status 2) or RunError (1).
// `check`, if set, checks the arguments that need no file (a scheme name, a
// range) right after the parse (cli.hpp, CommandLine::parse), throwing
// InputError or UsageError; it runs nothing and touches no file.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace lgi::experiments {

struct Subcommand {
  CLI::App* app = nullptr;
  std::function<int()> action;
  std::function<void()> check{};
};

/// The whole command line, for provenance in output files.
struct CommandContext {
  std::string command_line;
};

/// Declares one subcommand on the app (commands/all_commands.hpp lists them).
using CommandFactory = Subcommand (*)(CLI::App& app, const CommandContext& context);

}  // namespace lgi::experiments
