#pragma once
// The `lgi` command (README.md, "Using lgi"): subcommands, exit statuses
// (0 success, 1 the run failed, 2 bad command line or input) and one-line
// errors on stderr.
//
// Reading a command line and running it are two steps: CommandLine::parse
// reads argv and checks every argument that needs no file, and never runs a
// study, reads or writes a file, or ends the process (the fuzz harness
// fuzz/fuzz_command_line.cpp calls it alone); CommandLine::run then runs the
// subcommand it selected.
#include <CLI/CLI.hpp>
#include <optional>
#include <ostream>
#include <vector>

#include "experiments/cli/commands.hpp"

namespace lgi::experiments {

class CommandLine {
 public:
  /// Declares every subcommand of `commands` (the table main.cpp builds,
  /// commands/all_commands.hpp); argv[0] is the program. argv is read by parse().
  CommandLine(int argc, const char* const* argv, const std::vector<CommandFactory>& commands);
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  /// Parses argv and checks the selected subcommand's arguments that need no
  /// file. std::nullopt: a subcommand is ready to run(). Otherwise the exit
  /// status: 0 after --help or --version (their text written to `out`), 2
  /// after an error (one line on `err`, "lgi: ...").
  std::optional<int> parse(std::ostream& out, std::ostream& err);
  /// Runs the subcommand parse() selected; returns its exit status, errors
  /// as one line on `err`.
  int run(std::ostream& err) const;

 private:
  int argc_;
  const char* const* argv_;
  CLI::App app_;
  CommandContext context_;
  std::vector<Subcommand> subcommands_;
  const Subcommand* selected_ = nullptr;
};

/// parse(), then run() (std::cout, std::cerr): what `lgi` does.
int run_cli(int argc, char** argv, const std::vector<CommandFactory>& commands);

}  // namespace lgi::experiments
