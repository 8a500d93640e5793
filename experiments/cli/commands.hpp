#pragma once
// The subcommands of `lgi`. Each lives in its own commands/<name>_command.cpp and
// registers itself on the CLI11 app with add_<name>_subcommand(), which
// declares its options and returns the action to run when it is selected.
// Actions return an exit status (exit_status.hpp) and throw InputError /
// UsageError / OutputFileError for bad input (status 2) or RunError (1).
// `check`, if set, checks the arguments that need no file (a scheme name, a
// range) right after the parse (cli.hpp, CommandLine::parse), throwing
// InputError or UsageError; it runs nothing and touches no file.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <optional>
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

Subcommand add_simulate_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_schemes_subcommand(CLI::App& app);
Subcommand add_scenes_subcommand(CLI::App& app);
Subcommand add_work_precision_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_long_time_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_singularity_subcommand(CLI::App& app, const CommandContext& context);  // commands/singularity_command.cpp
Subcommand add_stress_subcommand(CLI::App& app, const CommandContext& context);  // commands/stress_command.cpp
Subcommand add_sweep_subcommand(CLI::App& app, const CommandContext& context);   // commands/sweep_command.cpp
/// `lgi sweep --spec SPEC --out OUT [--threads N] [--force] [--quiet]` without
/// its command line (lgi.sweep, python/): the same checks, run and file.
/// Returns the exit status; throws as the subcommand does.
struct SweepRequest {
  std::string spec, out;
  int threads = 0;  // 0: all cores
  bool force = false, quiet = true;
  std::string command_line;
};
int run_sweep_request(const SweepRequest& request);  // commands/sweep_command.cpp

Subcommand add_equilibria_subcommand(CLI::App& app, const CommandContext& context);  // commands/equilibria_command.cpp
Subcommand add_bifurcation_subcommand(CLI::App& app, const CommandContext& context);  // commands/equilibria_command.cpp
Subcommand add_poincare_subcommand(CLI::App& app, const CommandContext& context);  // commands/poincare_command.cpp
Subcommand add_periodic_subcommand(CLI::App& app, const CommandContext& context);  // commands/periodic_command.cpp
/// The flags of `lgi poincare` (experiments/POINCARE.md) as fields; run
/// without its command line by lgi.poincare (python/): the same checks, run
/// and file. Returns the exit status; throws as the subcommand does.
struct PoincareRequest {
  std::string scene, out = "poincare.h5", axis, section = "richter", scheme, seeds;  // scheme: empty is the default
  std::string measure;  // empty: liouville (a Cardan top refuses the flag)
  double l = 0.0, h = 0.0, t_end = 0.0, threshold = 3.0;
  std::optional<double> dt;
  std::int64_t ics = 0, max_events = 100000;
  std::uint64_t seed = 0;
  int threads = 0;  // 0: all cores
  bool lyapunov = false, megno = false, force = false, quiet = false;
  std::string command_line;
};
int run_poincare_request(const PoincareRequest& request);  // commands/poincare_command.cpp
Subcommand add_region_subcommand(CLI::App& app, const CommandContext& context);  // commands/region_command.cpp
Subcommand add_chaos_map_subcommand(CLI::App& app, const CommandContext& context);  // commands/chaos_map_command.cpp
Subcommand add_actions_subcommand(CLI::App& app, const CommandContext& context);  // commands/actions_command.cpp
Subcommand add_indicators_subcommand(CLI::App& app, const CommandContext& context);  // commands/indicators_command.cpp
Subcommand add_quantum_subcommand(CLI::App& app, const CommandContext& context);  // commands/quantum_command.cpp

}  // namespace lgi::experiments
