#pragma once
// The subcommands of `lgi`. Each returns an exit status (exit_status.hpp)
// and throws InputError / UsageError / OutputFileError for bad input, which
// run_cli turns into one line on stderr and status 2.
#include <cstdint>
#include <optional>
#include <string>

namespace lgi::experiments {

struct SimulateOptions {
  std::string scene;
  std::string scheme;
  std::optional<double> dt;
  std::optional<double> tol;
  std::optional<double> t_end;
  std::int64_t save_every = 1;
  std::string out;
  bool force = false;
  bool quiet = false;
  std::string command_line;
};
int simulate_command(const SimulateOptions& options);

struct SchemesOptions {
  bool json = false;
};
int schemes_command(const SchemesOptions& options);

struct ScenesOptions {
  std::string directory;
};
int scenes_command(const ScenesOptions& options);

}  // namespace lgi::experiments
